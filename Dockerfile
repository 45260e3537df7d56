# Build: release binary (SQLite is bundled and compiled with gcc; no other system library).
FROM rust:1.95-slim-bookworm AS build
WORKDIR /src
COPY Cargo.toml Cargo.lock ./
COPY migrations migrations
COPY src src
COPY crates crates
COPY benches benches
RUN cargo build --release --locked --bin tribod

# Run: slim Debian, non-root, the database on a volume.
FROM debian:bookworm-slim
RUN apt-get update \
    && apt-get install -y --no-install-recommends curl ca-certificates \
    && rm -rf /var/lib/apt/lists/* \
    && useradd --system --uid 10001 --home-dir /data --shell /usr/sbin/nologin tribod \
    && mkdir -p /data && chown tribod /data
COPY --from=build /src/target/release/tribod /usr/local/bin/tribod
USER tribod
WORKDIR /data
VOLUME ["/data"]
ENV TRIBOD_ADDR=0.0.0.0:8080 \
    TRIBOD_DATABASE_URL=/data/tribod.db \
    TRIBOD_LOG_FORMAT=json
EXPOSE 8080
HEALTHCHECK --interval=30s --timeout=3s --start-period=10s --retries=3 \
    CMD curl -fsS http://127.0.0.1:8080/healthz || exit 1
ENTRYPOINT ["tribod"]
CMD ["serve"]

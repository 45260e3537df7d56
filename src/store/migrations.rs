//! The schema migrations of both backends, embedded in the binary. Each backend's list names
//! every file of its `migrations/<backend>/` folder (a test checks the lists against the folders),
//! parsed as `sqlx`'s own folder reader does — `<version>_<description>.sql`, the description's
//! `_` read as spaces, `-- no-transaction` at the top to opt out of the transaction — so the
//! checksums recorded in existing databases stay valid. Built by hand rather than by
//! `sqlx::migrate!`, whose macro crate compiles both database drivers (and SQLite's C source) a
//! second time for the compiler host: about two minutes of every clean build.

use sqlx::migrate::{Migration, MigrationType, Migrator};
use sqlx::SqlSafeStr;
use std::borrow::Cow;

/// One migration file: its name in the folder and its SQL.
pub type MigrationFile = (&'static str, &'static str);

/// `migrations/sqlite/`, in version order.
pub const SQLITE: &[MigrationFile] = &[
    ("0001_jobs.sql", include_str!("../../migrations/sqlite/0001_jobs.sql")),
    ("0002_reliability.sql", include_str!("../../migrations/sqlite/0002_reliability.sql")),
    ("0003_leases.sql", include_str!("../../migrations/sqlite/0003_leases.sql")),
    ("0004_idempotency_keys.sql", include_str!("../../migrations/sqlite/0004_idempotency_keys.sql")),
    ("0005_estimates.sql", include_str!("../../migrations/sqlite/0005_estimates.sql")),
    ("0006_children.sql", include_str!("../../migrations/sqlite/0006_children.sql")),
    ("0007_short_jobs.sql", include_str!("../../migrations/sqlite/0007_short_jobs.sql")),
];

/// `migrations/postgres/`, in version order.
pub const POSTGRES: &[MigrationFile] = &[
    ("0001_jobs.sql", include_str!("../../migrations/postgres/0001_jobs.sql")),
    ("0002_idempotency_keys.sql", include_str!("../../migrations/postgres/0002_idempotency_keys.sql")),
    ("0003_estimates.sql", include_str!("../../migrations/postgres/0003_estimates.sql")),
    ("0004_hot_updates.sql", include_str!("../../migrations/postgres/0004_hot_updates.sql")),
    ("0005_children.sql", include_str!("../../migrations/postgres/0005_children.sql")),
    ("0006_no_status_index.sql", include_str!("../../migrations/postgres/0006_no_status_index.sql")),
    ("0007_short_jobs.sql", include_str!("../../migrations/postgres/0007_short_jobs.sql")),
];

/// The migrator of one backend's files.
pub fn migrator(files: &'static [MigrationFile]) -> Migrator {
    let migrations = files
        .iter()
        .map(|(name, sql)| {
            let (version, rest) = name.split_once('_').expect("migration file names are <version>_<description>.sql");
            let version: i64 = version.parse().expect("migration versions are integers");
            let description = rest.trim_end_matches(".sql").replace('_', " ");
            Migration::new(version, Cow::Owned(description), MigrationType::Simple, sql.into_sql_str(), sql.starts_with("-- no-transaction"))
        })
        .collect::<Vec<_>>();
    Migrator { migrations: Cow::Owned(migrations), ..Migrator::DEFAULT }
}

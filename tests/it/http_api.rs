//! The HTTP API end to end: a real server on a loopback port, a temporary SQLite file or a fresh
//! PostgreSQL database (every test runs on both backends), reqwest.


use crate::common::*;

on_both_backends!(
    submit_poll_and_fetch_result_json_and_csv,
    prefer_wait_returns_the_finished_job,
    list_filters_and_keyset_pagination,
    cancel_queued_and_running_then_delete,
    identical_specs_are_reused_unless_fresh,
    bad_inputs_are_4xx_problems_with_paths,
    timeouts_and_panics_fail_the_job_not_the_worker,
    full_backlog_answers_503_with_retry_after,
    progress_is_visible_while_running,
    bearer_tokens_guard_v1_but_not_operations,
    operations_endpoints_and_kinds,
    graceful_shutdown_requeues_unfinished_jobs,
    cors_is_off_by_default_and_configurable,
    events_follow_a_job_until_it_ends,
);
use serde_json::{json, Value};
use std::time::Duration;

const LONG: Duration = Duration::from_secs(20);

async fn submit_poll_and_fetch_result_json_and_csv() {
    let s = start().await;
    let res = s.post_job(&hertz_job(1000.0)).await;
    assert_eq!(res.status().as_u16(), 202);
    let location = res.headers()["location"].to_str().unwrap().to_string();
    let job: Value = res.json().await.unwrap();
    let id = job["id"].as_str().unwrap().to_string();
    assert_eq!(location, format!("/v1/jobs/{id}"));
    assert_eq!(job["status"], "queued");
    assert_eq!(job["kind"], "hertz");

    let done = s.wait_finished(&id, LONG).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    assert_eq!(done["attempts"], 1);
    assert_eq!(done["spec"]["profile_points"], 61, "canonical spec has defaults filled");

    let (status, result) = s.get_json(&format!("/v1/jobs/{id}/result")).await;
    assert_eq!(status, 200);
    // w' = 1e5 N/m on R = 0.02 m steel/steel: b = sqrt(4 w' R / (π E*)), E* = 210e9/(2·0.91).
    let es = 210e9 / (2.0 * 0.91);
    let b = (4.0 * 1e5 * 0.02 / (std::f64::consts::PI * es)).sqrt();
    let got = result["half_width"].as_f64().unwrap();
    assert!((got / b - 1.0).abs() < 1e-12, "half width {got} vs {b}");
    assert_eq!(result["meta"]["kind"], "hertz");
    assert_eq!(result["meta"]["job_id"], id.as_str());
    assert!(result["meta"]["wall_time_seconds"].as_f64().unwrap() >= 0.0);

    // CSV of a table that was not requested: by the Accept header, 406; by the query, 404.
    let res = s.client.get(s.url(&format!("/v1/jobs/{id}/result"))).header("accept", "text/csv").send().await.unwrap();
    let p = expect_problem(res, 406, "not_acceptable").await;
    assert!(p["detail"].as_str().unwrap().contains("stress_profile"));
    let res = s.client.get(s.url(&format!("/v1/jobs/{id}/result?format=csv"))).send().await.unwrap();
    expect_problem(res, 404, "table_not_found").await;
    // Another kind's table (a well-formed query this job cannot answer): 404; a name no kind
    // has (outside the document's enum): 400 naming the parameter.
    let res = s.client.get(s.url(&format!("/v1/jobs/{id}/result?format=csv&table=profile"))).send().await.unwrap();
    let p = expect_problem(res, 404, "table_not_found").await;
    assert!(p["detail"].as_str().unwrap().contains("stress_profile"), "{p}");
    let res = s.client.get(s.url(&format!("/v1/jobs/{id}/result?format=csv&table=nonsense"))).send().await.unwrap();
    let p = expect_problem(res, 400, "invalid_query").await;
    assert_eq!(p["errors"][0]["path"], "?table", "{p}");

    // With the profile requested, CSV works.
    let mut job = hertz_job(1000.0);
    job["spec"]["outputs"] = json!(["stress_profile"]);
    job["spec"]["profile_points"] = json!(11);
    let res = s.client.post(s.url("/v1/jobs")).header("prefer", "wait=10").json(&job).send().await.unwrap();
    assert_eq!(res.status().as_u16(), 200);
    let job: Value = res.json().await.unwrap();
    let res = s
        .client
        .get(s.url(&format!("/v1/jobs/{}/result", job["id"].as_str().unwrap())))
        .header("accept", "text/csv")
        .send()
        .await
        .unwrap();
    assert_eq!(res.status().as_u16(), 200);
    assert!(res.headers()["content-type"].to_str().unwrap().starts_with("text/csv"));
    let csv = res.text().await.unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 12, "{csv}");
    assert_eq!(lines[0], "depth [m],sigma_x [Pa],sigma_y [Pa],sigma_z [Pa],principal_shear [Pa],von_mises [Pa]");
    s.stop().await;
}

async fn prefer_wait_returns_the_finished_job() {
    let s = start().await;
    let res = s.client.post(s.url("/v1/jobs")).header("prefer", "respond-async, wait=10").json(&hertz_job(2000.0)).send().await.unwrap();
    assert_eq!(res.status().as_u16(), 200);
    assert_eq!(res.headers()["preference-applied"], "wait=10");
    let job: Value = res.json().await.unwrap();
    assert_eq!(job["status"], "succeeded");

    // A job slower than the wait comes back 202, still running or queued.
    let res = s.client.post(s.url("/v1/jobs")).header("prefer", "wait=0.2").json(&sleep_job(2.0, 1)).send().await.unwrap();
    assert_eq!(res.status().as_u16(), 202);
    let job: Value = res.json().await.unwrap();
    assert!(job["status"] == "running" || job["status"] == "queued", "{job}");
    s.stop().await;
}

async fn list_filters_and_keyset_pagination() {
    let s = start().await;
    let mut ids = Vec::new();
    for i in 0..5 {
        let res = s.client.post(s.url("/v1/jobs")).header("prefer", "wait=10").json(&hertz_job(100.0 + i as f64)).send().await.unwrap();
        let job: Value = res.json().await.unwrap();
        ids.push(job["id"].as_str().unwrap().to_string());
    }
    let res = s.post_job(&sleep_job(30.0, 7)).await;
    let sleeper: Value = res.json().await.unwrap();
    let sleeper_id = sleeper["id"].as_str().unwrap().to_string();

    // Pages of 2, newest first, following `next`.
    let mut seen = Vec::new();
    let mut after: Option<String> = None;
    loop {
        let path = match &after {
            Some(a) => format!("/v1/jobs?kind=hertz&limit=2&after={a}"),
            None => "/v1/jobs?kind=hertz&limit=2".to_string(),
        };
        let (status, page) = s.get_json(&path).await;
        assert_eq!(status, 200, "{page}");
        for j in page["jobs"].as_array().unwrap() {
            assert_eq!(j["kind"], "hertz");
            assert!(j.get("spec").is_none(), "listings do not carry specs");
            seen.push(j["id"].as_str().unwrap().to_string());
        }
        match page["next"].as_str() {
            Some(n) => after = Some(n.to_string()),
            None => break,
        }
    }
    let mut expected = ids.clone();
    expected.reverse();
    assert_eq!(seen, expected);

    // Status filter.
    let (_, page) = s.get_json("/v1/jobs?status=queued,running").await;
    let jobs = page["jobs"].as_array().unwrap();
    assert_eq!(jobs.len(), 1);
    assert_eq!(jobs[0]["id"], sleeper_id.as_str());
    let (_, page) = s.get_json("/v1/jobs?status=succeeded&limit=500").await;
    assert_eq!(page["jobs"].as_array().unwrap().len(), 5);

    // Time filters.
    let (_, page) = s.get_json("/v1/jobs?created_after=2000-01-01T00:00:00Z&created_before=2999-01-01T00:00:00Z").await;
    assert_eq!(page["jobs"].as_array().unwrap().len(), 6);
    let (_, page) = s.get_json("/v1/jobs?created_after=2999-01-01T00:00:00Z").await;
    assert_eq!(page["jobs"].as_array().unwrap().len(), 0);

    // Bad query parameters are 400 problems naming the parameter.
    for (q, param) in [
        ("status=sleeping", "?status"),
        ("limit=0", "?limit"),
        ("created_after=yesterday", "?created_after"),
        ("after=not-a-uuid", "?after"),
        ("colour=red", "?"),
    ] {
        let res = s.client.get(s.url(&format!("/v1/jobs?{q}"))).send().await.unwrap();
        let p = expect_problem(res, 400, "invalid_query").await;
        if param != "?" {
            assert_eq!(p["errors"][0]["path"], param, "{p}");
        }
    }
    let res = s.client.delete(s.url(&format!("/v1/jobs/{sleeper_id}"))).send().await.unwrap();
    assert_eq!(res.status().as_u16(), 202);

    // A cursor whose job was deleted between pages: the listing resumes where it stood (issue
    // 40), at the instant its UUIDv7 carries; older jobs all follow, the deleted one is gone.
    let res = s.client.delete(s.url(&format!("/v1/jobs/{}", ids[2]))).send().await.unwrap();
    assert_eq!(res.status().as_u16(), 204);
    let (status, page) = s.get_json(&format!("/v1/jobs?kind=hertz&after={}", ids[2])).await;
    assert_eq!(status, 200, "{page}");
    let listed: Vec<&str> = page["jobs"].as_array().unwrap().iter().map(|j| j["id"].as_str().unwrap()).collect();
    assert!(listed.ends_with(&[ids[1].as_str(), ids[0].as_str()]) && !listed.contains(&ids[2].as_str()), "{listed:?} vs {ids:?}");
    // An id this server never issues (a UUIDv4) names no place: an empty last page.
    let (status, page) = s.get_json("/v1/jobs?after=e3e70682-c209-4cac-a29f-6fbed82c07cd").await;
    assert_eq!((status, page["jobs"].as_array().map(Vec::len)), (200, Some(0)), "{page}");
    assert!(page.get("next").is_none(), "{page}");
    s.stop().await;
}

async fn cancel_queued_and_running_then_delete() {
    let s = start_with(|c| c.queue.workers = 1).await;
    let running: Value = s.post_job(&sleep_job(30.0, 1)).await.json().await.unwrap();
    let queued: Value = s.post_job(&sleep_job(30.0, 2)).await.json().await.unwrap();
    let (rid, qid) = (running["id"].as_str().unwrap().to_string(), queued["id"].as_str().unwrap().to_string());
    let r = s.wait_status(&rid, "running", LONG).await;
    assert_eq!(r["status"], "running");

    // Result of a running job: 409 result_not_ready.
    let res = s.client.get(s.url(&format!("/v1/jobs/{rid}/result"))).send().await.unwrap();
    expect_problem(res, 409, "result_not_ready").await;

    // Queued → canceled at once.
    let res = s.client.delete(s.url(&format!("/v1/jobs/{qid}"))).send().await.unwrap();
    assert_eq!(res.status().as_u16(), 200);
    let body: Value = res.json().await.unwrap();
    assert_eq!(body["status"], "canceled");

    // Running → cancel requested, stops within one step.
    let t0 = std::time::Instant::now();
    let res = s.client.delete(s.url(&format!("/v1/jobs/{rid}"))).send().await.unwrap();
    assert_eq!(res.status().as_u16(), 202);
    let body: Value = res.json().await.unwrap();
    assert_eq!(body["cancel_requested"], true);
    let done = s.wait_finished(&rid, LONG).await;
    assert_eq!(done["status"], "canceled");
    assert!(t0.elapsed() < Duration::from_secs(5), "cancel took {:?}", t0.elapsed());
    let res = s.client.get(s.url(&format!("/v1/jobs/{rid}/result"))).send().await.unwrap();
    expect_problem(res, 409, "result_unavailable").await;

    // Finished → deleted; deleting again is idempotent; then 404 on GET.
    for _ in 0..2 {
        let res = s.client.delete(s.url(&format!("/v1/jobs/{rid}"))).send().await.unwrap();
        assert_eq!(res.status().as_u16(), 204);
    }
    let res = s.client.get(s.url(&format!("/v1/jobs/{rid}"))).send().await.unwrap();
    expect_problem(res, 404, "job_not_found").await;
    s.stop().await;
}

async fn identical_specs_are_reused_unless_fresh() {
    let s = start().await;
    let first: Value = s.client.post(s.url("/v1/jobs")).header("prefer", "wait=10").json(&hertz_job(500.0)).send().await.unwrap().json().await.unwrap();
    assert_eq!(first["status"], "succeeded");

    // Same spec, keys reordered and defaults spelled out: the same job comes back.
    let same = json!({"spec": {
        "profile_points": 61, "outputs": [],
        "body_2": {"material": {"poisson_ratio": 0.3, "youngs_modulus": 210e9}, "shape": "flat"},
        "body_1": {"radius": 0.02, "shape": "cylinder"},
        "length": 0.01, "load": 500.0, "contact": "line"}, "kind": "hertz"});
    let res = s.post_job(&same).await;
    assert_eq!(res.status().as_u16(), 200);
    let again: Value = res.json().await.unwrap();
    assert_eq!(again["id"], first["id"]);
    assert_eq!(again["reused"], true);

    let res = s.client.post(s.url("/v1/jobs?fresh=true")).json(&same).send().await.unwrap();
    assert_eq!(res.status().as_u16(), 202);
    let fresh: Value = res.json().await.unwrap();
    assert_ne!(fresh["id"], first["id"]);
    assert_eq!(fresh["reused"], false);
    s.stop().await;
}

async fn bad_inputs_are_4xx_problems_with_paths() {
    let s = start_with(|c| c.api.body_limit = 4096).await;
    let post_raw = |body: &'static str| s.client.post(s.url("/v1/jobs")).header("content-type", "application/json").body(body).send();

    let p = expect_problem(post_raw("{\"kind\": \"hertz\", ").await.unwrap(), 400, "malformed_json").await;
    assert!(p["detail"].as_str().unwrap().contains("line 1"), "{p}");

    let p = expect_problem(s.post_job(&json!({"kind": "teleport", "spec": {}})).await, 422, "unknown_kind").await;
    assert_eq!(p["errors"][0]["path"], "/kind");
    assert!(p["detail"].as_str().unwrap().contains("hertz"), "lists the known kinds: {p}");

    let p = expect_problem(s.post_job(&json!({"kind": "hertz", "spec": {}, "colour": 1})).await, 422, "invalid_request").await;
    assert_eq!(p["errors"][0]["path"], "/colour");

    let mut job = hertz_job(1.0);
    job["spec"]["bogus"] = json!(true);
    let p = expect_problem(s.post_job(&job).await, 422, "invalid_spec").await;
    assert_eq!(p["errors"][0]["path"], "/spec/bogus");

    let mut job = hertz_job(1.0);
    job["spec"]["body_1"]["shape"] = json!("pyramid");
    let p = expect_problem(s.post_job(&job).await, 422, "invalid_spec").await;
    assert_eq!(p["errors"][0]["path"], "/spec/body_1/shape");

    let mut job = hertz_job(-5.0);
    job["spec"]["body_2"]["material"] = json!({"poisson_ratio": 0.7});
    let p = expect_problem(s.post_job(&job).await, 422, "invalid_spec").await;
    let paths: Vec<&str> = p["errors"].as_array().unwrap().iter().map(|e| e["path"].as_str().unwrap()).collect();
    assert_eq!(paths, ["/spec/load", "/spec/body_2/material/poisson_ratio"], "{p}");
    // The rule with its unit, and the value given.
    let message = p["errors"][0]["message"].as_str().unwrap();
    assert!(message.contains("between 0.001 N and 1e8 N") && message.contains("was given -5"), "{message}");

    let mut job = hertz_job(1.0);
    job["spec"]["load"] = json!("heavy");
    let p = expect_problem(s.post_job(&job).await, 422, "invalid_spec").await;
    assert_eq!(p["errors"][0]["path"], "/spec/load");

    let big = format!("{{\"kind\": \"hertz\", \"spec\": {{}}, \"label\": \"{}\"}}", "x".repeat(10_000));
    let res = s.client.post(s.url("/v1/jobs")).header("content-type", "application/json").body(big).send().await.unwrap();
    expect_problem(res, 413, "payload_too_large").await;

    let res = s.client.post(s.url("/v1/jobs")).header("content-type", "application/xml").body("<job/>").send().await.unwrap();
    expect_problem(res, 415, "unsupported_media_type").await;

    let res = s.client.get(s.url("/v1/nothing")).send().await.unwrap();
    expect_problem(res, 404, "route_not_found").await;
    let res = s.client.put(s.url("/v1/jobs")).send().await.unwrap();
    expect_problem(res, 405, "method_not_allowed").await;
    let res = s.client.get(s.url("/v1/jobs/not-a-uuid")).send().await.unwrap();
    expect_problem(res, 404, "job_not_found").await;
    let p = expect_problem(s.post_job(&json!({"kind": "hertz"})).await, 422, "invalid_request").await;
    assert_eq!(p["errors"][0]["path"], "/spec", "{p}");
    let mut job = hertz_job(1.0);
    job["spec"].as_object_mut().unwrap().remove("body_2");
    let p = expect_problem(s.post_job(&job).await, 422, "invalid_spec").await;
    assert_eq!(p["errors"][0]["path"], "/spec/body_2", "{p}");
    let res = s.client.get(s.url(&format!("/v1/jobs/{}", uuid::Uuid::nil()))).send().await.unwrap();
    expect_problem(res, 404, "job_not_found").await;
    s.stop().await;
}

async fn timeouts_and_panics_fail_the_job_not_the_worker() {
    let s = start_with(|c| {
        c.queue.workers = 1;
        c.queue.job_timeout = Some(Duration::from_millis(300));
    })
    .await;
    let job: Value = s.post_job(&sleep_job(10.0, 1)).await.json().await.unwrap();
    let done = s.wait_finished(job["id"].as_str().unwrap(), LONG).await;
    assert_eq!(done["status"], "failed");
    assert_eq!(done["error"]["code"], "timeout", "{done}");

    let panicking = json!({"kind": "test_sleep", "spec": {"seconds": 0.05, "panic": true}});
    let job: Value = s.post_job(&panicking).await.json().await.unwrap();
    let done = s.wait_finished(job["id"].as_str().unwrap(), LONG).await;
    assert_eq!(done["status"], "failed");
    assert_eq!(done["error"]["code"], "internal_error");
    assert!(done["error"]["detail"].as_str().unwrap().contains("panicked"));

    // The single worker lives on.
    let res = s.client.post(s.url("/v1/jobs")).header("prefer", "wait=10").json(&hertz_job(9.0)).send().await.unwrap();
    let job: Value = res.json().await.unwrap();
    assert_eq!(job["status"], "succeeded");
    s.stop().await;
}

async fn full_backlog_answers_503_with_retry_after() {
    let s = start_with(|c| {
        c.queue.workers = 1;
        c.queue.max_backlog = 1;
    })
    .await;
    let running: Value = s.post_job(&sleep_job(30.0, 1)).await.json().await.unwrap();
    s.wait_status(running["id"].as_str().unwrap(), "running", LONG).await;
    let queued = s.post_job(&sleep_job(30.0, 2)).await;
    assert_eq!(queued.status().as_u16(), 202);
    let res = s.post_job(&sleep_job(30.0, 3)).await;
    assert!(res.headers().get("retry-after").is_some());
    expect_problem(res, 503, "queue_full").await;
    s.stop().await;
}

async fn progress_is_visible_while_running() {
    let s = start().await;
    let job: Value = s.post_job(&sleep_job(1.5, 9)).await.json().await.unwrap();
    let id = job["id"].as_str().unwrap().to_string();
    let start = std::time::Instant::now();
    let mut seen = 0.0;
    while start.elapsed() < Duration::from_secs(10) {
        let (_, j) = s.get_json(&format!("/v1/jobs/{id}")).await;
        if j["status"] == "running" {
            seen = j["progress"]["fraction"].as_f64().unwrap();
            if seen > 0.0 {
                assert_eq!(j["progress"]["stage"], "sleeping");
                break;
            }
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    assert!(seen > 0.0 && seen < 1.0, "progress {seen}");
    let done = s.wait_finished(&id, LONG).await;
    assert_eq!(done["progress"]["fraction"], 1.0);
    s.stop().await;
}

async fn bearer_tokens_guard_v1_but_not_operations() {
    let s = start_with(|c| c.api.tokens = vec!["s3cret".into(), "other".into()]).await;
    let res = s.client.get(s.url("/v1/kinds")).send().await.unwrap();
    assert_eq!(res.headers()["www-authenticate"], "Bearer");
    expect_problem(res, 401, "unauthorized").await;
    let res = s.client.get(s.url("/v1/kinds")).bearer_auth("wrong").send().await.unwrap();
    expect_problem(res, 401, "unauthorized").await;
    let res = s.post_job(&hertz_job(1.0)).await;
    expect_problem(res, 401, "unauthorized").await;
    for token in ["s3cret", "other"] {
        let res = s.client.get(s.url("/v1/kinds")).bearer_auth(token).send().await.unwrap();
        assert_eq!(res.status().as_u16(), 200);
    }
    for open in ["/healthz", "/readyz", "/metrics", "/openapi.json"] {
        let res = s.client.get(s.url(open)).send().await.unwrap();
        assert_eq!(res.status().as_u16(), 200, "{open}");
    }
    s.stop().await;
}

async fn operations_endpoints_and_kinds() {
    let s = start().await;
    let res = s.client.get(s.url("/healthz")).send().await.unwrap();
    assert_eq!(res.text().await.unwrap(), "ok");
    let res = s.client.get(s.url("/readyz")).send().await.unwrap();
    assert_eq!(res.text().await.unwrap(), "ready");

    let (status, kinds) = s.get_json("/v1/kinds").await;
    assert_eq!(status, 200);
    let kinds = kinds["kinds"].as_array().unwrap();
    let hertz = kinds.iter().find(|k| k["name"] == "hertz").unwrap();
    assert_eq!(hertz["tables"], json!(["stress_profile"]));
    assert_eq!(hertz["spec_schema"], "#/components/schemas/HertzSpec");
    // Every example spec is valid: submitting it succeeds.
    for k in kinds {
        let res = s
            .client
            .post(s.url("/v1/jobs"))
            .header("prefer", "wait=30")
            .json(&json!({"kind": k["name"], "spec": k["example"]}))
            .send()
            .await
            .unwrap();
        let mut job: Value = res.json().await.unwrap();
        // A loaded machine can take longer than the 30 s wait (the wear example's 1000 h); the
        // job then keeps running and must still succeed.
        if job["status"] == "running" || job["status"] == "queued" {
            job = s.wait_status(job["id"].as_str().unwrap(), "succeeded", Duration::from_secs(300)).await;
        }
        assert_eq!(job["status"], "succeeded", "example of {}: {job}", k["name"]);
    }

    let text = s.client.get(s.url("/metrics")).send().await.unwrap().text().await.unwrap();
    for needle in ["tribod_jobs{status=\"succeeded\"}", "tribod_queue_depth", "tribod_job_solve_seconds_bucket", "tribod_jobs_submitted_total"] {
        assert!(text.contains(needle), "metrics lack {needle}:\n{text}");
    }
    let (status, doc) = s.get_json("/openapi.json").await;
    assert_eq!(status, 200);
    assert!(doc["paths"]["/v1/jobs"]["post"].is_object());
    s.stop().await;
}

async fn graceful_shutdown_requeues_unfinished_jobs() {
    let dir = tempfile::tempdir().unwrap();
    let mut cfg = test_config(&dir).await;
    cfg.shutdown_grace = Duration::from_millis(200);
    cfg.queue.workers = 1;
    let s = start_in(dir, cfg.clone()).await;
    let long: Value = s.post_job(&sleep_job(1.5, 11)).await.json().await.unwrap();
    let id = long["id"].as_str().unwrap().to_string();
    s.wait_status(&id, "running", LONG).await;
    let dir = s.stop().await;

    // Restart on the same file: the job runs again from the queue and finishes; attempts stay 1
    // because a shutdown interruption is not counted.
    let s = start_in(dir, cfg).await;
    let done = s.wait_finished(&id, LONG).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    assert_eq!(done["attempts"], 1);
    s.stop().await;
}

async fn cors_is_off_by_default_and_configurable() {
    let s = start().await;
    let res = s.client.get(s.url("/v1/kinds")).header("origin", "https://dash.example").send().await.unwrap();
    assert!(res.headers().get("access-control-allow-origin").is_none());
    s.stop().await;

    let s = start_with(|c| c.api.cors_origins = vec!["https://dash.example".into()]).await;
    let res = s
        .client
        .request(reqwest::Method::OPTIONS, s.url("/v1/jobs"))
        .header("origin", "https://dash.example")
        .header("access-control-request-method", "POST")
        .header("access-control-request-headers", "content-type,prefer")
        .send()
        .await
        .unwrap();
    assert!(res.status().is_success(), "{}", res.status());
    assert_eq!(res.headers()["access-control-allow-origin"], "https://dash.example");
    let res = s.client.get(s.url("/v1/kinds")).header("origin", "https://evil.example").send().await.unwrap();
    assert!(res.headers().get("access-control-allow-origin").is_none());
    s.stop().await;
}

/// Parse a Server-Sent Events body into `(event, data)` pairs (comments and keep-alives skipped).
pub fn sse_events(text: &str) -> Vec<(String, String)> {
    text.split("\n\n")
        .filter_map(|block| {
            let mut name = None;
            let mut data = Vec::new();
            for line in block.lines() {
                if let Some(v) = line.strip_prefix("event:") {
                    name = Some(v.trim().to_string());
                } else if let Some(v) = line.strip_prefix("data:") {
                    data.push(v.strip_prefix(' ').unwrap_or(v).to_string());
                }
            }
            name.map(|n| (n, data.join("\n")))
        })
        .collect()
}

async fn events_follow_a_job_until_it_ends() {
    let s = start_with(|c| c.queue.workers = 1).await;
    // A job that runs about a second, reporting progress as it goes.
    let job: Value = s.post_job(&sleep_job(1.0, 77)).await.json().await.unwrap();
    let id = job["id"].as_str().unwrap().to_string();
    let mut res = s
        .client
        .get(s.url(&format!("/v1/jobs/{id}/events")))
        .header("accept", "text/event-stream")
        .send()
        .await
        .unwrap();
    assert_eq!(res.status(), 200);
    assert_eq!(res.headers()["content-type"], "text/event-stream");
    // The stream ends by itself when the job ends.
    let mut body = String::new();
    let read = tokio::time::timeout(LONG, async {
        while let Some(chunk) = res.chunk().await.unwrap() {
            body.push_str(&String::from_utf8_lossy(&chunk));
        }
    })
    .await;
    assert!(read.is_ok(), "the stream did not end with the job: {body}");
    let events = sse_events(&body);
    let names: Vec<&str> = events.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names.first(), Some(&"status"), "{names:?}");
    assert_eq!(names.last(), Some(&"done"), "{names:?}");
    assert!(names.iter().filter(|n| **n == "done").count() == 1);
    assert!(names.contains(&"progress"), "progress of a 1 s job is seen: {names:?}");
    // Events come in order: statuses never go back, progress never decreases.
    let jobs: Vec<Value> = events.iter().map(|(_, d)| serde_json::from_str(d).unwrap()).collect();
    let rank = |s: &str| match s { "queued" => 0, "running" => 1, _ => 2 };
    for w in jobs.windows(2) {
        assert!(rank(w[0]["status"].as_str().unwrap()) <= rank(w[1]["status"].as_str().unwrap()), "{w:?}");
        assert!(w[0]["progress"]["fraction"].as_f64() <= w[1]["progress"]["fraction"].as_f64(), "{w:?}");
    }
    assert_eq!(jobs.last().unwrap()["status"], "succeeded");
    assert_eq!(jobs.last().unwrap()["id"], id.as_str());

    // A finished job: one `done` event, then the end. An unknown job: 404 problem.
    let text = s.client.get(s.url(&format!("/v1/jobs/{id}/events"))).send().await.unwrap().text().await.unwrap();
    let names: Vec<String> = sse_events(&text).into_iter().map(|(n, _)| n).collect();
    assert_eq!(names, ["done"]);
    let res = s.client.get(s.url(&format!("/v1/jobs/{}/events", uuid::Uuid::now_v7()))).send().await.unwrap();
    expect_problem(res, 404, "job_not_found").await;
    s.stop().await;
}

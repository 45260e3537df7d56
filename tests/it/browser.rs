//! The dashboard and the API docs (issue 13): served as pages, and driven end to end in a real
//! headless Chromium over the DevTools protocol — the seed 002 L9 example submitted through the
//! form against a server that needs a token, followed until it finishes, its plots opened and a
//! screenshot taken; a bad spec shows the server's field errors; no console errors anywhere.
//! And (issue 39) the example picker and the schema form of the new-job page, the key-results
//! card's units, plausibility warnings, interactive uPlot charts (hover, zoom, legend toggles) and
//! the comparison of jobs.
//!
//! The browser test needs Chromium (`apt-get install chromium`; `.ci/run` installs it). Without
//! one it prints SKIPPED and passes; `TRIBOD_CHROMIUM=/path/to/chrome` picks another binary.

use crate::common::*;
use futures_util::{SinkExt, StreamExt};
use serde_json::{json, Value};
use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};
use tokio_tungstenite::tungstenite::Message;

const TOKEN: &str = "browser-test-token";

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn dashboard_and_docs_are_served_without_a_token() {
    let s = start_with(|c| c.api.tokens = vec![TOKEN.into()]).await;
    for (path, content_type, needle) in [
        ("/", "text/html", "<main id=\"view\""),
        ("/assets/app.js", "text/javascript", "/v1/jobs"),
        ("/assets/style.css", "text/css", "progress"),
        ("/assets/vendor/uPlot.iife.min.js", "text/javascript", "uPlot"),
        ("/assets/vendor/uPlot.min.css", "text/css", ".u-legend"),
        ("/assets/examples.json", "application/json", "\"file\""),
        ("/docs", "text/html", "swagger-ui"),
        ("/docs/swagger-initializer.js", "text/javascript", "\"/openapi.json\""),
    ] {
        let res = s.client.get(s.url(path)).header("accept", "text/html,*/*;q=0.8").send().await.unwrap();
        assert_eq!(res.status(), 200, "{path}");
        let ct = res.headers()["content-type"].to_str().unwrap().to_string();
        assert!(ct.starts_with(content_type), "{path}: {ct}");
        if path == "/" || path.starts_with("/assets/") {
            let csp = res.headers()["content-security-policy"].to_str().unwrap().to_string();
            assert!(csp.contains("script-src 'self'") && csp.contains("style-src 'self'"), "{path}: {csp}");
        }
        let text = res.text().await.unwrap();
        assert!(text.contains(needle), "{path}: no '{needle}'");
    }
    // The page loads uPlot (vendored) before the app.
    let page = s.client.get(s.url("/")).send().await.unwrap().text().await.unwrap();
    let (uplot, app) = (page.find("/assets/vendor/uPlot.iife.min.js").unwrap(), page.find("/assets/app.js").unwrap());
    assert!(uplot < app, "uPlot loads before app.js");
    // Every example of examples/ is embedded, as it is on disk.
    let served: Value = s.client.get(s.url("/assets/examples.json")).send().await.unwrap().json().await.unwrap();
    let mut on_disk: Vec<String> = std::fs::read_dir("examples")
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".json"))
        .collect();
    on_disk.sort();
    let listed: Vec<String> = served.as_array().unwrap().iter().map(|e| e["file"].as_str().unwrap().to_string()).collect();
    assert_eq!(listed, on_disk, "src/web/mod.rs EXAMPLES lists every examples/*.json");
    for e in served.as_array().unwrap() {
        let file: Value = serde_json::from_str(&std::fs::read_to_string(format!("examples/{}", e["file"].as_str().unwrap())).unwrap()).unwrap();
        assert_eq!((&e["kind"], &e["spec"]), (&file["kind"], &file["spec"]), "{}", e["file"]);
    }
    // The docs page resolves its files under /docs/ also when opened as /docs.
    let page = s.client.get(s.url("/docs")).send().await.unwrap().text().await.unwrap();
    assert!(page.contains("<base href=\"/docs/\">"));
    // The API itself still needs the token.
    let res = s.client.get(s.url("/v1/jobs")).send().await.unwrap();
    expect_problem(res, 401, "unauthorized").await;
    let res = s.client.get(s.url("/docs/nope.js")).send().await.unwrap();
    expect_problem(res, 404, "route_not_found").await;
    s.stop().await;
}

/// The Chromium binary, if there is one.
fn chromium() -> Option<String> {
    if let Ok(p) = std::env::var("TRIBOD_CHROMIUM") {
        return Some(p);
    }
    ["chromium", "chromium-browser", "google-chrome", "google-chrome-stable"].into_iter().find_map(|name| {
        std::env::var_os("PATH")?.to_str()?.split(':').map(|d| format!("{d}/{name}")).find(|p| std::path::Path::new(p).is_file())
    })
}

/// A headless Chromium with its DevTools endpoint; killed on drop.
struct Browser {
    child: Child,
    port: u16,
    _profile: tempfile::TempDir,
}

impl Browser {
    fn launch(binary: &str) -> Browser {
        let profile = tempfile::tempdir().unwrap();
        let mut child = Command::new(binary)
            .args([
                "--headless=new",
                "--no-sandbox",
                "--disable-gpu",
                "--disable-dev-shm-usage",
                "--no-first-run",
                "--no-default-browser-check",
                "--remote-debugging-port=0",
                "--window-size=1280,1000",
            ])
            .arg(format!("--user-data-dir={}", profile.path().display()))
            .arg("about:blank")
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("chromium starts");
        // "DevTools listening on ws://127.0.0.1:<port>/devtools/browser/<id>"
        let stderr = child.stderr.take().unwrap();
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stderr).lines().map_while(Result::ok) {
                if let Some(rest) = line.split("ws://127.0.0.1:").nth(1) {
                    let _ = tx.send(rest.split('/').next().unwrap_or("").parse::<u16>().ok());
                }
            }
        });
        let port = rx.recv_timeout(Duration::from_secs(30)).ok().flatten().expect("chromium prints its DevTools port");
        Browser { child, port, _profile: profile }
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

type Socket = tokio_tungstenite::WebSocketStream<tokio_tungstenite::MaybeTlsStream<tokio::net::TcpStream>>;

/// One page over the DevTools protocol: commands, and the console errors, exceptions and failed
/// loads it reported.
struct Page {
    ws: Socket,
    next: u64,
    errors: Vec<String>,
}

impl Page {
    async fn open(browser: &Browser) -> Page {
        let targets: Value = reqwest::get(format!("http://127.0.0.1:{}/json/list", browser.port)).await.unwrap().json().await.unwrap();
        let url = targets.as_array().unwrap().iter().find(|t| t["type"] == "page").expect("a page target")["webSocketDebuggerUrl"]
            .as_str()
            .unwrap()
            .to_string();
        let (ws, _) = tokio_tungstenite::connect_async(url).await.expect("DevTools socket");
        let mut page = Page { ws, next: 0, errors: Vec::new() };
        for domain in ["Page.enable", "Runtime.enable", "Log.enable", "Network.enable"] {
            page.call(domain, json!({})).await;
        }
        page
    }

    async fn call(&mut self, method: &str, params: Value) -> Value {
        self.next += 1;
        let id = self.next;
        self.ws.send(Message::text(json!({"id": id, "method": method, "params": params}).to_string())).await.unwrap();
        loop {
            let msg = tokio::time::timeout(Duration::from_secs(60), self.ws.next()).await.expect("DevTools answers").unwrap().unwrap();
            let Ok(text) = msg.into_text() else { continue };
            let v: Value = serde_json::from_str(text.as_str()).unwrap();
            if v["id"] == id {
                assert!(v.get("error").is_none(), "{method}: {}", v["error"]);
                return v["result"].clone();
            }
            self.note(&v);
        }
    }

    /// Keeps what the page reported that a user would see as an error in the console.
    fn note(&mut self, event: &Value) {
        let p = &event["params"];
        match event["method"].as_str().unwrap_or("") {
            "Runtime.exceptionThrown" => self.errors.push(format!("exception: {}", p["exceptionDetails"])),
            "Runtime.consoleAPICalled" if p["type"] == "error" => self.errors.push(format!("console.error: {}", p["args"])),
            "Log.entryAdded" if p["entry"]["level"] == "error" => {
                self.errors.push(format!("log[{}]: {}", p["entry"]["source"].as_str().unwrap_or(""), p["entry"]["text"]))
            }
            _ => {}
        }
    }

    /// Evaluates `expression` (statements allowed, in a block of their own; the last one's value
    /// is returned, a promise awaited).
    async fn eval(&mut self, expression: &str) -> Value {
        let block = format!("{{\n{expression}\n}}");
        let r = self.call("Runtime.evaluate", json!({"expression": block, "awaitPromise": true, "returnByValue": true})).await;
        assert!(r.get("exceptionDetails").is_none(), "{expression}: {}", r["exceptionDetails"]);
        r["result"]["value"].clone()
    }

    /// Waits until `condition` (a JS expression) is truthy.
    async fn wait_for(&mut self, condition: &str, timeout: Duration) {
        let start = Instant::now();
        loop {
            let v = self.eval(&format!("Boolean({condition})")).await;
            if v == true {
                return;
            }
            assert!(start.elapsed() < timeout, "timed out waiting for {condition}; page: {}", self.eval("document.body.innerText").await);
            tokio::time::sleep(Duration::from_millis(100)).await;
        }
    }

    async fn navigate(&mut self, url: &str) {
        self.call("Page.navigate", json!({"url": url})).await;
        self.wait_for("document.readyState === 'complete'", Duration::from_secs(20)).await;
    }

    /// A mouse event at page coordinates (`kind`: mousePressed, mouseMoved, mouseReleased).
    async fn mouse(&mut self, kind: &str, x: f64, y: f64, pressed: bool, clicks: u32) {
        let button = if pressed || kind != "mouseMoved" { "left" } else { "none" };
        self.call(
            "Input.dispatchMouseEvent",
            json!({"type": kind, "x": x, "y": y, "button": button, "buttons": if pressed { 1 } else { 0 }, "clickCount": clicks}),
        )
        .await;
    }

    /// The viewport rectangle `[left, top, width, height]` of the first element matching
    /// `selector`, scrolled into view.
    async fn rect(&mut self, selector: &str) -> [f64; 4] {
        let r = self
            .eval(&format!(
                "const e = document.querySelector({}); e.scrollIntoView({{block: 'center'}}); const r = e.getBoundingClientRect(); [r.left, r.top, r.width, r.height]",
                js(selector)
            ))
            .await;
        let v: Vec<f64> = r.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        [v[0], v[1], v[2], v[3]]
    }

    async fn screenshot(&mut self, path: &std::path::Path) {
        let r = self.call("Page.captureScreenshot", json!({"format": "png", "captureBeyondViewport": false})).await;
        let bytes = decode_base64(r["data"].as_str().unwrap());
        assert!(bytes.starts_with(b"\x89PNG"), "not a PNG");
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, bytes).unwrap();
    }
}

fn decode_base64(s: &str) -> Vec<u8> {
    let value = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        _ => 63,
    };
    let clean: Vec<u8> = s.bytes().filter(|c| *c != b'=' && !c.is_ascii_whitespace()).collect();
    let mut out = Vec::with_capacity(clean.len() * 3 / 4);
    for chunk in clean.chunks(4) {
        let n = chunk.iter().enumerate().fold(0u32, |acc, (i, c)| acc | (u32::from(value(*c)) << (18 - 6 * i)));
        out.extend_from_slice(&n.to_be_bytes()[1..chunk.len()]);
    }
    out
}

/// JS string literal of `s`.
fn js(s: &str) -> String {
    serde_json::to_string(s).unwrap()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_dashboard_runs_the_seed002_l9_example_in_a_real_browser() {
    let Some(binary) = chromium() else {
        eprintln!(
            "SKIPPED the_dashboard_runs_the_seed002_l9_example_in_a_real_browser: no Chromium on PATH. \
             Install it (`apt-get install chromium`) or set TRIBOD_CHROMIUM, then `cargo test --test it browser`."
        );
        return;
    };
    let s = start_with(|c| c.api.tokens = vec![TOKEN.into()]).await;
    let browser = Browser::launch(&binary);
    let mut page = Page::open(&browser).await;
    let wait = Duration::from_secs(30);

    // The list, empty; without a token the page asks for one.
    page.navigate(&s.url("/")).await;
    page.wait_for("!document.getElementById('notice').hidden", wait).await;
    let notice = page.eval("document.getElementById('notice').textContent").await;
    assert!(notice.as_str().unwrap().contains("token"), "{notice}");
    // The token, entered once (kept in the tab's session storage).
    page.eval(&format!("document.getElementById('token').value = {}; document.querySelector('#token-form button').click()", js(TOKEN))).await;
    page.wait_for("document.querySelector('#jobs td')", wait).await;
    assert_eq!(page.eval("sessionStorage.getItem('tribod-token')").await, TOKEN);

    // A bad spec: the server's problem, with the offending field's path beside the editor.
    page.eval("document.getElementById('nav-new').click()").await;
    page.wait_for("document.getElementById('spec') && document.getElementById('spec').value.length > 10", wait).await;
    page.eval(
        "const k = document.getElementById('kind'); k.value = 'bearing_optimisation'; k.dispatchEvent(new Event('change'));
         const t = document.getElementById('spec'); const spec = JSON.parse(t.value); spec.base.grid.circumferential = 3;
         t.value = JSON.stringify(spec, null, 2); document.getElementById('submit').click()",
    )
    .await;
    page.wait_for("document.querySelector('.field-error')", wait).await;
    let path = page.eval("document.querySelector('.field-error').dataset.path").await;
    assert_eq!(path, "/spec/base/grid/circumferential", "field error path");
    // "show" selects the field in the editor.
    page.eval("document.querySelector('.field-error button').click()").await;
    let selected = page.eval("const t = document.getElementById('spec'); t.value.slice(t.selectionStart, t.selectionEnd)").await;
    assert_eq!(selected, "\"circumferential\"");

    // The seed 002 L9 example through the form.
    let example: Value = serde_json::from_str(&std::fs::read_to_string("examples/seed002_taguchi_l9.json").unwrap()).unwrap();
    assert_eq!(example["kind"], "bearing_optimisation");
    let spec = serde_json::to_string_pretty(&example["spec"]).unwrap();
    page.eval(&format!(
        "document.getElementById('spec').value = {}; document.getElementById('label').value = 'seed 002 L9 from the browser';
         document.getElementById('submit').click()",
        js(&spec)
    ))
    .await;
    page.wait_for("location.hash.startsWith('#/jobs/')", wait).await;
    let id = page.eval("location.hash.slice(7)").await.as_str().unwrap().to_string();
    // Followed live until it finishes, then its plots load.
    page.wait_for("document.querySelector('#job-status [data-status=succeeded]')", Duration::from_secs(120)).await;
    page.wait_for(
        "(() => { const imgs = [...document.querySelectorAll('#plots img')];
                  return imgs.length >= 2 && imgs.every(i => i.complete && i.naturalWidth > 0); })()",
        wait,
    )
    .await;
    let plots = page.eval("[...document.querySelectorAll('#plots img')].map(i => i.dataset.plot)").await;
    assert_eq!(plots, json!(["main_effects", "run_scores"]));
    let summary = page.eval("document.getElementById('summary').innerText").await;
    assert!(summary.as_str().unwrap().contains("best_run"), "{summary}");
    let tables = page.eval("[...document.querySelectorAll('#downloads [data-table]')].map(b => b.dataset.table)").await;
    assert!(tables.as_array().is_some_and(|t| !t.is_empty()), "{tables}");
    // What the page shows is what the API stored.
    let stored: Value = s.client.get(s.url(&format!("/v1/jobs/{id}/result"))).bearer_auth(TOKEN).send().await.unwrap().json().await.unwrap();
    assert!(summary.as_str().unwrap().contains(&format!("best_run\t{}", stored["best_run"])), "{summary}");
    let shot = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("dashboard-l9.png");
    page.screenshot(&shot).await;
    eprintln!("screenshot: {}", shot.display());

    // The list shows it, filtered by kind and status.
    page.eval("location.hash = '#/?kind=bearing_optimisation&status=succeeded'").await;
    page.wait_for(&format!("document.querySelector('#jobs tr[data-id={}]')", js(&id)), wait).await;
    // Everything fits on one page: no "older jobs" button.
    assert_eq!(page.eval("document.getElementById('more').hidden").await, true);
    // Past 50 jobs the list offers the older ones.
    for i in 0..60 {
        let res = s.client.post(s.url("/v1/jobs")).bearer_auth(TOKEN).json(&hertz_job(100.0 + i as f64)).send().await.unwrap();
        assert!(res.status().is_success(), "{}", res.status());
    }
    page.eval("location.hash = '#/?kind=hertz'").await;
    page.wait_for("document.querySelectorAll('#jobs tr.job').length === 50 && !document.getElementById('more').hidden", wait).await;
    page.eval("document.getElementById('more').click()").await;
    page.wait_for("document.querySelectorAll('#jobs tr.job').length === 60 && document.getElementById('more').hidden", wait).await;

    page.eval("location.hash = '#/?kind=bearing_optimisation'").await;
    page.wait_for(&format!("document.querySelector('#jobs tr[data-id={}]')", js(&id)), wait).await;
    // Keyboard: Enter on a focused job row opens it.
    page.eval(&format!("document.querySelector('#jobs tr[data-id={}]').focus()", js(&id))).await;
    for kind in ["keyDown", "keyUp"] {
        page.call("Input.dispatchKeyEvent", json!({"type": kind, "key": "Enter", "code": "Enter", "windowsVirtualKeyCode": 13})).await;
    }
    page.wait_for(&format!("location.hash === '#/jobs/' + {}", js(&id)), wait).await;

    // The API docs render the document.
    page.navigate(&s.url("/docs")).await;
    page.wait_for("document.querySelectorAll('.opblock').length >= 8", wait).await;

    // The browser itself logs the two refused requests the test provoked (401 without the token,
    // 422 for the bad spec) as network errors; anything else is a defect of the page.
    page.errors.retain(|e| !(e.starts_with("log[network]") && (e.contains("status of 401") || e.contains("status of 422"))));
    assert!(page.errors.is_empty(), "console errors: {:#?}", page.errors);
    drop(page);
    drop(browser);
    s.stop().await;
}

/// Sets a form control's value and fires `input` as a person's edit would.
fn set_input(selector: &str, value: &str) -> String {
    format!(
        "const e = document.querySelector({}); e.value = {}; e.dispatchEvent(new Event('input', {{bubbles: true}}));",
        js(selector),
        js(value)
    )
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_dashboard_picks_examples_edits_specs_as_a_form_charts_and_compares_jobs() {
    let Some(binary) = chromium() else {
        eprintln!(
            "SKIPPED the_dashboard_picks_examples_edits_specs_as_a_form_charts_and_compares_jobs: no Chromium on PATH. \
             Install it (`apt-get install chromium`) or set TRIBOD_CHROMIUM, then `cargo test --test it browser`."
        );
        return;
    };
    let s = start().await;
    let browser = Browser::launch(&binary);
    let mut page = Page::open(&browser).await;
    let wait = Duration::from_secs(30);
    let spec_of_editor = "JSON.parse(document.getElementById('spec').value)";

    // The example picker lists every example and fills kind, label and spec from one.
    page.navigate(&s.url("/#/new")).await;
    page.wait_for("document.querySelectorAll('#example option').length > 1", wait).await;
    let files = std::fs::read_dir("examples").unwrap().filter(|e| e.as_ref().unwrap().path().extension().is_some_and(|x| x == "json")).count();
    let offered = page.eval("document.querySelectorAll('#example option:not([value=\"\"])').length").await;
    assert_eq!(offered, json!(files), "one choice per examples/*.json");
    let example: Value = serde_json::from_str(&std::fs::read_to_string("examples/hertz_roller_on_cam.json").unwrap()).unwrap();
    page.eval("const x = document.getElementById('example'); x.value = 'hertz_roller_on_cam.json'; x.dispatchEvent(new Event('change'))").await;
    assert_eq!(page.eval("document.getElementById('kind').value").await, "hertz");
    assert_eq!(page.eval("document.getElementById('label').value").await, example["label"]);
    let same = page.eval(&format!("JSON.stringify({spec_of_editor}) === JSON.stringify({})", example["spec"])).await;
    assert_eq!(same, true, "the editor holds the example's spec");

    // The form (from the kind's schema in /openapi.json) shows the same spec: a field per
    // property with its description and range, enums as selects, nested objects as fieldsets.
    let radius = "#spec-form [data-pointer=\"/body_1/radius\"]";
    page.wait_for(&format!("document.querySelector({})", js(radius)), wait).await;
    assert_eq!(page.eval(&format!("document.querySelector({}).value", js(radius))).await, "0.0255");
    assert_eq!(page.eval("document.querySelector('#spec-form select[data-pointer=\"/contact\"]').value").await, "\"line\"");
    assert_eq!(page.eval("document.querySelector('#spec-form fieldset[data-pointer=\"/body_1\"] legend').textContent").await, "body_1");
    let hint = page.eval("document.querySelector('#spec-form [data-pointer=\"/load\"]').closest('.field').innerText").await;
    assert!(hint.as_str().unwrap().contains("Total normal load, N.") && hint.as_str().unwrap().contains("≥ 0.001"), "{hint}");
    // The editor drives the form while it parses; invalid JSON leaves the form as it was.
    page.eval("const t = document.getElementById('spec'); const v = JSON.parse(t.value); v.load = 7000; t.value = JSON.stringify(v, null, 2); t.dispatchEvent(new Event('input'))").await;
    assert_eq!(page.eval("document.querySelector('#spec-form [data-pointer=\"/load\"]').value").await, "7000");
    page.eval("const t = document.getElementById('spec'); t.value = t.value.replace('7000', '70 00'); t.dispatchEvent(new Event('input'))").await;
    assert_eq!(page.eval("document.querySelector('#spec-form [data-pointer=\"/load\"]').value").await, "7000");
    assert!(page.eval("document.getElementById('spec-status').textContent").await.as_str().unwrap().contains("JSON"));
    // The form drives the editor: an implausible radius (millimetres where SI wants metres).
    page.eval(&set_input(radius, "25.5")).await;
    let edited = page.eval(spec_of_editor).await;
    assert_eq!(edited["body_1"]["radius"], 25.5);
    assert_eq!(edited["load"], 7000.0, "the form edited its last valid spec");
    assert_eq!(page.eval("document.getElementById('spec-status').textContent").await, "");
    page.eval("document.getElementById('submit').click()").await;
    page.wait_for("location.hash.startsWith('#/jobs/')", wait).await;
    page.wait_for("document.querySelector('#job-status [data-status=succeeded]') && document.getElementById('key-results')", wait).await;
    // The job page warns about the implausible field, by its path.
    let warned = page.eval("[...document.querySelectorAll('#job-warnings .field-warning')].map(w => w.dataset.path)").await;
    assert_eq!(warned, json!(["/spec/body_1/radius"]));
    // The key-results card shows engineering units.
    let card = page.eval("document.getElementById('key-results').innerText").await.as_str().unwrap().to_string();
    assert!(card.contains("max_pressure") && (card.contains("GPa") || card.contains("MPa")), "{card}");
    assert!(card.contains(" mm") || card.contains(" µm"), "{card}");

    // A cam_cycle job (the kind's example, fidelity fast) through the form: its curves as
    // interactive charts.
    page.eval("document.getElementById('nav-new').click()").await;
    page.wait_for("document.getElementById('kind') && location.hash === '#/new'", wait).await;
    page.eval("const k = document.getElementById('kind'); k.value = 'cam_cycle'; k.dispatchEvent(new Event('change'))").await;
    page.wait_for("document.querySelector('#spec-form [data-pointer=\"/fidelity\"]')", wait).await;
    page.eval(&set_input("#spec-form [data-pointer=\"/fidelity\"]", "\"fast\"")).await;
    assert_eq!(page.eval(&format!("{spec_of_editor}.fidelity")).await, "fast");
    assert_eq!(page.eval("document.getElementById('label').value").await, "", "the hertz example's label went with it");
    // A tagged union is a select of its variants.
    let variants = page.eval("[...document.querySelectorAll('#spec-form select[data-variant=\"/follower\"] option')].map(o => o.value).filter(Boolean)").await;
    assert!(variants.as_array().unwrap().len() >= 2 && variants.as_array().unwrap().contains(&json!("flat_faced")), "{variants}");
    page.eval("document.getElementById('label').value = 'cam fast A'; document.getElementById('submit').click()").await;
    page.wait_for("location.hash.startsWith('#/jobs/')", wait).await;
    let cam_a = page.eval("location.hash.slice(7)").await.as_str().unwrap().to_string();
    page.wait_for("document.querySelector('#job-status [data-status=succeeded]') && document.querySelector('#charts canvas')", wait).await;
    let card = page.eval("document.getElementById('key-results').innerText").await.as_str().unwrap().to_string();
    assert!(card.contains("MPa") || card.contains("GPa"), "{card}");
    // One chart per unit group, films together in µm or nm, against the cam angle.
    let film = "#charts figure.chart[data-columns*=\"film_min\"]";
    let columns = page.eval(&format!("document.querySelector({}).dataset.columns", js(film))).await;
    assert!(columns.as_str().unwrap().split(',').all(|c| c.contains("film")), "{columns}");
    let unit = page.eval(&format!("document.querySelector({} + ' .chart-box').dataset.unit", js(film))).await;
    assert!(unit == "µm" || unit == "nm", "{unit}");
    assert!(page.eval(&format!("document.querySelector({}).innerText", js(film))).await.as_str().unwrap().contains("angle_deg"));
    // The server's SVG plots stay, below.
    assert_eq!(page.eval("document.querySelectorAll('#server-plots #plots figure').length > 0").await, true);
    // Hover: the legend reads the values under the cursor, with the unit.
    let [left, top, width, height] = page.rect(&format!("{film} .u-over")).await;
    page.mouse("mouseMoved", left + width * 0.4, top + height / 2.0, false, 0).await;
    let reading = format!("document.querySelector({} + ' .u-legend .u-series:nth-child(2) .u-value').textContent", js(film));
    page.wait_for(&format!("{reading}.endsWith({})", js(&format!(" {}", unit.as_str().unwrap()))), wait).await;
    // Drag to zoom, double-click to reset.
    let zoomed = format!("document.querySelector({} + ' .chart-box').dataset.zoomed", js(film));
    assert_eq!(page.eval(&zoomed).await, "false");
    page.mouse("mousePressed", left + width * 0.3, top + height / 2.0, true, 1).await;
    page.mouse("mouseMoved", left + width * 0.5, top + height / 2.0, true, 0).await;
    page.mouse("mouseMoved", left + width * 0.6, top + height / 2.0, true, 0).await;
    page.mouse("mouseReleased", left + width * 0.6, top + height / 2.0, false, 1).await;
    page.wait_for(&format!("{zoomed} === 'true'"), wait).await;
    for clicks in [1, 2] {
        page.mouse("mousePressed", left + width * 0.5, top + height / 2.0, true, clicks).await;
        page.mouse("mouseReleased", left + width * 0.5, top + height / 2.0, false, clicks).await;
    }
    page.wait_for(&format!("{zoomed} === 'false'"), wait).await;
    // A legend entry toggles its series.
    let entry = format!("{film} .u-legend .u-series:nth-child(2)");
    let off = format!("document.querySelector({}).classList.contains('u-off')", js(&entry));
    for hidden in [true, false] {
        let [left, top, width, height] = page.rect(&format!("{entry} th")).await;
        page.mouse("mousePressed", left + width / 2.0, top + height / 2.0, true, 1).await;
        page.mouse("mouseReleased", left + width / 2.0, top + height / 2.0, false, 1).await;
        page.wait_for(&format!("{off} === {hidden}"), wait).await;
    }
    let shot = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("dashboard-cam-charts.png");
    page.screenshot(&shot).await;

    // A second cam job, faster; both ticked on the list and compared.
    let kinds: Value = s.get_json("/v1/kinds").await.1;
    let mut spec = kinds["kinds"].as_array().unwrap().iter().find(|k| k["name"] == "cam_cycle").unwrap()["example"].clone();
    spec["fidelity"] = json!("fast");
    spec["operation"]["speed_rpm"] = json!(2000.0);
    let res = s.post_job(&json!({"kind": "cam_cycle", "label": "cam fast B", "spec": spec})).await;
    assert!(res.status().is_success(), "{}", res.status());
    let cam_b = res.json::<Value>().await.unwrap()["id"].as_str().unwrap().to_string();
    assert_eq!(s.wait_finished(&cam_b, wait).await["status"], "succeeded");
    page.eval("location.hash = '#/?kind=cam_cycle'").await;
    for id in [&cam_a, &cam_b] {
        page.wait_for(&format!("document.querySelector('#jobs input.pick[data-id={}]')", js(id)), wait).await;
    }
    assert_eq!(page.eval("document.getElementById('compare').disabled").await, true, "one job is no comparison");
    for id in [&cam_a, &cam_b] {
        page.eval(&format!("document.querySelector('#jobs input.pick[data-id={}]').click()", js(id))).await;
    }
    assert_eq!(page.eval("location.hash").await, "#/?kind=cam_cycle", "ticking a job does not open it");
    page.eval("document.getElementById('compare').click()").await;
    let url = format!("#/compare?ids={cam_a},{cam_b}");
    page.wait_for(&format!("location.hash === {}", js(&url)), wait).await;
    // The comparison's address reopens it.
    page.navigate(&s.url(&format!("/{url}"))).await;
    page.wait_for("document.querySelector('#compare-chart canvas')", wait).await;
    // Key results side by side: a column per job (by label), a row per figure with its unit.
    let heads = page.eval("[...document.querySelectorAll('#compare-table thead th[data-id]')].map(t => t.querySelector('a').textContent)").await;
    assert_eq!(heads, json!(["cam fast A", "cam fast B"]));
    let row = page.eval("[...document.querySelector('#compare-table tr[data-path=\"summary.min_film\"]').cells].map(c => c.textContent)").await;
    let row: Vec<&str> = row.as_array().unwrap().iter().map(|c| c.as_str().unwrap()).collect();
    assert_eq!(row.len(), 4, "{row:?}");
    assert!(row[1] == "nm" || row[1] == "µm", "{row:?}");
    assert!(row[2].parse::<f64>().is_ok() && row[3].parse::<f64>().is_ok() && row[2] != row[3], "{row:?}");
    // One curve overlaid, a series per job: the first film column by default.
    assert_eq!(page.eval("document.getElementById('compare-column').value").await, "series.film_min");
    assert_eq!(page.eval("document.getElementById('compare-chart').dataset.series").await, "2");
    let legend = page.eval("[...document.querySelectorAll('#compare-chart .u-legend .u-series')].slice(1).map(s => s.querySelector('.u-label').textContent)").await;
    assert_eq!(legend, json!(["cam fast A", "cam fast B"]));
    // Another column redraws it.
    page.eval("const c = document.getElementById('compare-column'); c.value = 'series.hertz_max_pressure'; c.dispatchEvent(new Event('change'))").await;
    page.wait_for("document.getElementById('compare-chart').dataset.unit === 'MPa' || document.getElementById('compare-chart').dataset.unit === 'GPa'", wait).await;
    assert_eq!(page.eval("document.querySelectorAll('#compare-chart canvas').length").await, 1);
    let shot = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("dashboard-compare.png");
    page.screenshot(&shot).await;
    eprintln!("screenshot: {}", shot.display());

    assert!(page.errors.is_empty(), "console errors: {:#?}", page.errors);
    drop(page);
    drop(browser);
    s.stop().await;
}

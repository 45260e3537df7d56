// tribod dashboard: plain JavaScript over the public API (/v1). Three views chosen by the URL
// hash: the job list (#/), the submit form (#/new) and a job (#/jobs/<id>). The bearer token,
// when the server needs one, is kept in this tab's session storage and sent on every request;
// the live stream and the plots are fetched with it too (EventSource and <img> cannot send it).
"use strict";

const TOKEN_KEY = "tribod-token";
const ACTIVE = new Set(["queued", "running"]);
const view = () => document.getElementById("view");
let kindsCache = null;
let leave = () => {}; // stops what the current view started (timers, streams, object URLs)

// ---- helpers ----------------------------------------------------------------------------------

// A job's short id: the random tail of its UUIDv7 (the head is its creation time, the same for
// every job submitted within a few milliseconds).
function shortId(id) {
  return id.replace(/-/g, "").slice(-8);
}

// A file-name stem for a job's downloads: its label (or kind) and short id.
function fileStem(job, id) {
  const base = (job.label || job.kind).replace(/#[0-9a-f]+/g, "").replace(/[^A-Za-z0-9._-]+/g, "_").replace(/^_+|_+$/g, "").slice(0, 60);
  return (base || job.kind) + "-" + shortId(id);
}

function h(tag, attrs, ...children) {
  const el = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (v === undefined || v === null || v === false) continue;
    if (k.startsWith("on")) el.addEventListener(k.slice(2), v);
    else if (k === "dataset") Object.assign(el.dataset, v);
    else el.setAttribute(k, v === true ? "" : String(v));
  }
  for (const c of children.flat()) {
    if (c === undefined || c === null || c === false) continue;
    el.append(c instanceof Node ? c : document.createTextNode(String(c)));
  }
  return el;
}

function notice(text) {
  const n = document.getElementById("notice");
  n.textContent = text || "";
  n.hidden = !text;
}

async function api(path, options = {}) {
  const headers = new Headers(options.headers || {});
  const token = sessionStorage.getItem(TOKEN_KEY);
  if (token) headers.set("Authorization", "Bearer " + token);
  const res = await fetch(path, { ...options, headers });
  if (res.status === 401) {
    notice("This server needs an API token: enter it at the top right and press Use.");
    document.getElementById("token").focus();
  }
  return res;
}

async function json(path, options) {
  const res = await api(path, options);
  let body = null;
  try { body = await res.json(); } catch (_) { body = null; }
  return { res, body };
}

function fmt(v) {
  if (typeof v === "number") {
    if (!Number.isFinite(v)) return String(v);
    if (Number.isInteger(v) && Math.abs(v) < 1e9) return String(v);
    const a = Math.abs(v);
    return a !== 0 && (a < 1e-3 || a >= 1e6) ? v.toExponential(4) : String(Number(v.toPrecision(5)));
  }
  if (typeof v === "boolean") return v ? "yes" : "no";
  return String(v);
}

function when(iso) {
  if (!iso) return "";
  const d = new Date(iso);
  return Number.isNaN(d.getTime()) ? iso : d.toLocaleString();
}

function statusBadge(status) {
  return h("span", { class: "status " + status, "data-status": status }, status);
}

function progressCell(job) {
  if (!ACTIVE.has(job.status)) return statusBadge(job.status);
  const p = job.progress || {};
  return h("span", {},
    statusBadge(job.status), " ",
    h("progress", { max: 1, value: p.fraction || 0, "aria-label": "progress" }),
    p.stage ? h("span", { class: "stage" }, p.stage) : null);
}

async function kinds() {
  if (!kindsCache) {
    const { res, body } = await json("/v1/kinds");
    if (!res.ok || !body) throw new Error("could not read /v1/kinds (" + res.status + ")");
    kindsCache = body.kinds;
  }
  return kindsCache;
}

function download(blob, name) {
  const url = URL.createObjectURL(blob);
  const a = h("a", { href: url, download: name });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

// Server-Sent Events read from a fetch body, so the token header can be sent.
async function follow(path, onEvent, signal) {
  const res = await api(path, { signal, headers: { Accept: "text/event-stream" } });
  if (!res.ok || !res.body) return;
  const reader = res.body.pipeThrough(new TextDecoderStream()).getReader();
  let buffer = "";
  for (;;) {
    const { value, done } = await reader.read();
    if (done) return;
    buffer += value.replace(/\r\n/g, "\n");
    let cut;
    while ((cut = buffer.indexOf("\n\n")) >= 0) {
      const block = buffer.slice(0, cut);
      buffer = buffer.slice(cut + 2);
      let event = "message";
      let data = "";
      for (const line of block.split("\n")) {
        if (line.startsWith("event:")) event = line.slice(6).trim();
        else if (line.startsWith("data:")) data += line.slice(5).replace(/^ /, "");
      }
      if (data) {
        try { onEvent(event, JSON.parse(data)); } catch (_) { /* not JSON: ignore */ }
      }
    }
  }
}

// ---- the job list -----------------------------------------------------------------------------

async function listView(params) {
  const root = view();
  const all = await kinds();
  const kindSelect = h("select", { id: "filter-kind", name: "kind" }, h("option", { value: "" }, "all kinds"),
    all.map((k) => h("option", { value: k.name }, k.name)));
  const statusSelect = h("select", { id: "filter-status", name: "status" },
    ["", "queued,running", "queued", "running", "succeeded", "failed", "canceled"].map((s) =>
      h("option", { value: s }, s === "" ? "any status" : s === "queued,running" ? "queued or running" : s)));
  kindSelect.value = params.get("kind") || "";
  statusSelect.value = params.get("status") || "";
  const body = h("tbody", { id: "jobs" });
  // The newest `shown` jobs (the API pages by 500 at most; filters narrow further).
  let shown = 50;
  const more = h("button", { class: "secondary", type: "button", id: "more", hidden: true,
    onclick: () => { shown = Math.min(500, shown + 100); load(); } }, "Show older jobs");
  const refresh = h("button", { class: "secondary", type: "button", onclick: () => load() }, "Refresh");
  const onFilter = () => {
    const q = new URLSearchParams();
    if (kindSelect.value) q.set("kind", kindSelect.value);
    if (statusSelect.value) q.set("status", statusSelect.value);
    location.hash = "#/" + (q.toString() ? "?" + q : "");
  };
  kindSelect.addEventListener("change", onFilter);
  statusSelect.addEventListener("change", onFilter);
  root.replaceChildren(
    h("h1", {}, "Jobs"),
    h("div", { class: "filters" },
      h("label", {}, "Kind", kindSelect), h("label", {}, "Status", statusSelect), refresh,
      h("a", { href: "#/new" }, "Submit a job…")),
    h("table", {},
      h("thead", {}, h("tr", {}, ["Job", "Kind", "Status", "Created", "Finished"].map((c) => h("th", { scope: "col" }, c)))),
      body),
    h("div", { class: "actions" }, more));

  let timer = null;
  let stopped = false;
  async function load() {
    clearTimeout(timer);
    const q = new URLSearchParams({ limit: String(shown) });
    if (kindSelect.value) q.set("kind", kindSelect.value);
    if (statusSelect.value) q.set("status", statusSelect.value);
    const { res, body: page } = await json("/v1/jobs?" + q);
    if (stopped) return;
    if (!res.ok || !page) {
      body.replaceChildren(h("tr", {}, h("td", { colspan: 5 }, (page && page.detail) || "could not list jobs (" + res.status + ")")));
      return;
    }
    if (page.jobs.length === 0) {
      body.replaceChildren(h("tr", {}, h("td", { colspan: 5, class: "muted" }, "No jobs yet. ", h("a", { href: "#/new" }, "Submit one."))));
    } else {
      body.replaceChildren(...page.jobs.map((j) => {
        const open = () => { location.hash = "#/jobs/" + j.id; };
        return h("tr", { class: "job", tabindex: 0, "data-id": j.id, onclick: open, onkeydown: (e) => { if (e.key === "Enter") open(); } },
          h("td", {}, h("a", { href: "#/jobs/" + j.id }, j.label || shortId(j.id))),
          h("td", {}, j.kind),
          h("td", {}, progressCell(j)),
          h("td", {}, when(j.created_at)),
          h("td", {}, when(j.finished_at)));
      }));
    }
    more.hidden = !page.next || shown >= 500;
    // Progress of the list: refreshed while something on it is moving (a job's own page
    // follows it live over its event stream).
    if (page.jobs.some((j) => ACTIVE.has(j.status))) timer = setTimeout(load, 1500);
  }
  await load();
  leave = () => { stopped = true; clearTimeout(timer); };
}

// ---- the submit form --------------------------------------------------------------------------

function fieldKey(path) {
  const parts = path.split("/").filter(Boolean);
  while (parts.length && /^\d+$/.test(parts[parts.length - 1])) parts.pop();
  return parts.length ? parts[parts.length - 1].replace(/~1/g, "/").replace(/~0/g, "~") : null;
}

// Selects `"key"` of the offending field in the editor (the first occurrence after its parents').
function showField(textarea, path) {
  const parts = path.split("/").filter(Boolean).filter((p) => !/^\d+$/.test(p));
  if (parts[0] === "spec") parts.shift();
  let from = 0;
  let at = -1;
  for (const p of parts) {
    const i = textarea.value.indexOf('"' + p + '"', from);
    if (i < 0) break;
    at = i;
    from = i + 1;
  }
  textarea.focus();
  if (at >= 0) {
    const key = fieldKey(path) || "";
    textarea.setSelectionRange(at, at + key.length + 2);
    const line = textarea.value.slice(0, at).split("\n").length;
    textarea.scrollTop = Math.max(0, (line - 5) * 18);
  }
}

async function newView(params) {
  const root = view();
  const all = await kinds();
  const choice = params.get("kind") || "bearing_optimisation";
  const kindSelect = h("select", { id: "kind", name: "kind" }, all.map((k) => h("option", { value: k.name }, k.name)));
  kindSelect.value = all.some((k) => k.name === choice) ? choice : all[0].name;
  const label = h("input", { id: "label", type: "text", name: "label", placeholder: "what this run is (optional)" });
  const editor = h("textarea", { id: "spec", name: "spec", spellcheck: "false", "aria-label": "job spec (JSON)" });
  const description = h("p", { class: "muted", id: "kind-description" });
  const problems = h("div", { id: "problems", "aria-live": "polite" });
  const submit = h("button", { type: "submit", id: "submit" }, "Submit");
  const fill = () => {
    const k = all.find((x) => x.name === kindSelect.value);
    editor.value = JSON.stringify(k.example, null, 2);
    description.textContent = k.description;
    problems.replaceChildren();
  };
  kindSelect.addEventListener("change", fill);
  fill();

  const form = h("form", { id: "job-form", onsubmit: async (e) => {
    e.preventDefault();
    problems.replaceChildren();
    let spec;
    try {
      spec = JSON.parse(editor.value);
    } catch (err) {
      problems.replaceChildren(h("div", { class: "problem" }, h("h2", {}, "Not JSON"), h("p", {}, String(err.message))));
      return;
    }
    submit.disabled = true;
    const request = { kind: kindSelect.value, spec };
    if (label.value.trim()) request.label = label.value.trim();
    try {
      const { res, body } = await json("/v1/jobs", { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(request) });
      if (res.ok && body && body.id) {
        location.hash = "#/jobs/" + body.id;
        return;
      }
      showProblem(problems, body, res.status, editor);
    } finally {
      submit.disabled = false;
    }
  } },
  h("div", { class: "row" },
    h("label", {}, "Kind", kindSelect),
    h("label", {}, "Label", label),
    h("button", { type: "button", class: "secondary", onclick: fill }, "Reset to the example"),
    submit),
  description,
  h("div", { class: "editor" }, editor, problems));
  root.replaceChildren(h("h1", {}, "Submit a job"), form);
  leave = () => {};
}

function showProblem(where, problem, status, editor) {
  if (!problem) {
    where.replaceChildren(h("div", { class: "problem" }, h("h2", {}, "Request failed"), h("p", {}, "HTTP " + status)));
    return;
  }
  const items = (problem.errors || []).map((e) =>
    h("li", { class: "field-error", "data-path": e.path },
      h("code", {}, e.path), " ", e.message,
      editor ? h("button", { type: "button", class: "secondary", onclick: () => showField(editor, e.path), "aria-label": "show " + e.path + " in the spec" }, "show") : null));
  where.replaceChildren(h("div", { class: "problem", role: "alert" },
    h("h2", {}, problem.title || "Error"),
    h("p", {}, problem.detail || ""),
    h("p", { class: "muted" }, "code ", h("code", {}, problem.code || String(status))),
    items.length ? h("ul", {}, items) : null));
}

// ---- one job ----------------------------------------------------------------------------------

// Engineering multiples of the SI units the results use (the plots' own scaling, plots::scale).
const MULTIPLES = {
  "m": [[1e-9, "nm"], [1e-6, "µm"], [1e-3, "mm"], [1, "m"]],
  "Pa": [[1, "Pa"], [1e3, "kPa"], [1e6, "MPa"], [1e9, "GPa"]],
  "N": [[1, "N"], [1e3, "kN"], [1e6, "MN"]],
  "W": [[1e-3, "mW"], [1, "W"], [1e3, "kW"]],
  "N·m": [[1e-3, "N·mm"], [1, "N·m"]],
  "Pa·s": [[1e-3, "mPa·s"], [1, "Pa·s"]],
  "m³/s": [[1e-9, "mm³/s"], [1e-6, "cm³/s"], [1e-3, "L/s"], [1, "m³/s"]],
  "s": [[1e-6, "µs"], [1e-3, "ms"], [1, "s"]],
};

// A number with its unit, in the multiple that suits it, to 4 significant figures.
function withUnit(v, unit) {
  if (typeof v !== "number" || !Number.isFinite(v)) return fmt(v);
  let factor = 1, shown = unit === "1" ? "" : (unit || "");
  const steps = MULTIPLES[unit];
  if (steps && v !== 0) {
    let pick = steps[0];
    for (const s of steps) if (Math.abs(v) >= 0.1 * s[0]) pick = s; // 0.3 µm, not 300 nm
    [factor, shown] = pick;
  }
  const x = v / factor;
  const text = Number.isInteger(x) && Math.abs(x) < 1e9 ? String(x) : String(Number(x.toPrecision(4)));
  return shown ? text + " " + shown : text;
}

// The unit of a result field (dotted path) from the kind's `result_units` (GET /v1/kinds).
function unitOf(kind, path) {
  const units = (kind && kind.result_units) || {};
  const pointer = "/" + path.split(".").join("/");
  return units[pointer] ?? units[pointer.replace(/\/\d+(?=\/|$)/g, "/*")] ?? "";
}

function summaryRows(result) {
  const rows = [];
  const walk = (value, prefix) => {
    if (rows.length >= 80 || value === null || value === undefined) return;
    if (Array.isArray(value)) return; // tables: CSV and plots
    if (typeof value === "object") {
      for (const [k, v] of Object.entries(value)) walk(v, prefix ? prefix + "." + k : k);
      return;
    }
    rows.push([prefix, value]);
  };
  walk(result, "");
  return rows;
}

async function jobView(id) {
  const root = view();
  const controller = new AbortController();
  const urls = [];
  let stopped = false;
  leave = () => { stopped = true; controller.abort(); urls.forEach((u) => URL.revokeObjectURL(u)); };

  const head = h("div", { id: "job-head" });
  const actions = h("div", { class: "actions", id: "job-actions" });
  const body = h("div", { id: "job-body" });
  root.replaceChildren(h("h1", {}, "Job ", h("code", {}, shortId(id))), head, actions, body);

  const { res, body: first } = await json("/v1/jobs/" + id);
  if (!res.ok || !first) {
    showProblem(body, first, res.status);
    return;
  }
  let shown = null;
  const render = async (job) => {
    if (stopped) return;
    head.replaceChildren(h("dl", { class: "meta" },
      h("dt", {}, "Kind"), h("dd", {}, job.kind),
      job.label ? [h("dt", {}, "Label"), h("dd", {}, job.label)] : null,
      h("dt", {}, "Status"), h("dd", { id: "job-status" }, progressCell(job)),
      h("dt", {}, "Created"), h("dd", {}, when(job.created_at)),
      job.finished_at ? [h("dt", {}, "Finished"), h("dd", {}, when(job.finished_at))] : null,
      h("dt", {}, "Attempts"), h("dd", {}, job.attempts),
      h("dt", {}, "Solver"), h("dd", {}, job.solver_version)),
      ...((job.warnings || []).length ? [h("div", { class: "warnings", id: "job-warnings", role: "status" }, h("h2", {}, "Warnings"),
        h("ul", {}, job.warnings.map((w) => h("li", { class: "field-warning", "data-path": w.path }, h("code", {}, w.path), " ", w.message))))] : []));
    const active = ACTIVE.has(job.status);
    actions.replaceChildren(
      h("button", { type: "button", class: "danger", id: active ? "cancel" : "delete", onclick: async () => {
        if (!active && !confirm("Delete this job and its result?")) return;
        const r = await api("/v1/jobs/" + id, { method: "DELETE" });
        if (!active && r.ok) location.hash = "#/";
      } }, active ? "Cancel" : "Delete"),
      h("a", { href: "#/new?kind=" + encodeURIComponent(job.kind) }, "New " + job.kind + " job"));
    if (active || shown === job.status) return;
    shown = job.status;
    await finished(job);
  };

  const finished = async (job) => {
    if (job.status === "failed" || job.status === "canceled") {
      body.replaceChildren();
      if (job.error) showProblem(body, job.error, job.error.status);
      if (job.status === "canceled") body.append(h("p", { class: "muted" }, "This job was canceled."));
      return;
    }
    const [{ res: rr, body: result }, { body: list }, all] = await Promise.all([
      json("/v1/jobs/" + id + "/result"), json("/v1/jobs/" + id + "/plots"), kinds()]);
    if (stopped) return;
    if (!rr.ok || !result) {
      showProblem(body, result, rr.status);
      return;
    }
    const kind = all.find((k) => k.name === job.kind);
    const downloads = h("div", { class: "actions", id: "downloads" },
      h("button", { type: "button", class: "secondary", onclick: () =>
        download(new Blob([JSON.stringify(result, null, 2)], { type: "application/json" }), fileStem(job, id) + ".json") }, "Download JSON"),
      ((kind && kind.tables) || []).filter((t) => result[t] != null).map((t) => h("button", { type: "button", class: "secondary", "data-table": t, onclick: async () => {
        const r = await api("/v1/jobs/" + id + "/result?format=csv&table=" + encodeURIComponent(t), { headers: { Accept: "text/csv" } });
        if (r.ok) download(await r.blob(), fileStem(job, id) + "-" + t + ".csv");
        else notice("No CSV for table " + t + " (" + r.status + ")");
      } }, "CSV: " + t)));
    const plots = h("div", { class: "plots", id: "plots" });
    const summary = summaryRows(result);
    const key = summaryRows({ summary: result.summary, checks: result.checks }).filter(([, v]) => typeof v === "number" || typeof v === "boolean");
    const cell = ([k, v]) => h("tr", {}, h("td", {}, k),
      h("td", { class: typeof v === "number" ? "num" : (v === false ? "fail" : "") }, withUnit(v, unitOf(kind, k))));
    body.replaceChildren(
      ...(key.length ? [h("section", { class: "card", id: "key-results" }, h("h2", {}, "Key results"),
        h("table", { class: "summary" }, h("tbody", {}, key.map(cell))))] : []),
      h("h2", {}, "Plots"), plots,
      h("h2", {}, "Downloads"), downloads,
      h("h2", {}, "All figures"),
      summary.length
        ? h("table", { class: "summary", id: "summary" }, h("tbody", {}, summary.map(cell)))
        : h("p", { class: "muted" }, "The result is all tables: see the CSV downloads."));
    const names = (list && list.plots) || [];
    if (names.length === 0) plots.replaceChildren(h("p", { class: "muted" }, "No plots for this result."));
    for (const p of names) {
      const img = h("img", { alt: p.title, "data-plot": p.name, width: 900, height: 520 });
      const link = h("a", { href: "#", onclick: (e) => { e.preventDefault(); if (img.src) window.open(img.src, "_blank"); } }, "open");
      plots.append(h("figure", {}, img, h("figcaption", {}, p.title, " · ", link)));
      api(p.href, { signal: controller.signal }).then(async (r) => {
        if (!r.ok) return;
        const url = URL.createObjectURL(await r.blob());
        urls.push(url);
        img.src = url;
      }).catch(() => {});
    }
  };

  await render(first);
  if (ACTIVE.has(first.status)) {
    follow("/v1/jobs/" + id + "/events", (event, job) => { render(job); }, controller.signal).catch(() => {});
  }
}

// ---- routing ----------------------------------------------------------------------------------

async function route() {
  leave();
  leave = () => {};
  notice("");
  const hash = location.hash || "#/";
  const [path, query] = hash.slice(1).split("?");
  const params = new URLSearchParams(query || "");
  for (const [id, on] of [["nav-jobs", path === "/"], ["nav-new", path === "/new"]]) {
    const a = document.getElementById(id);
    if (on) a.setAttribute("aria-current", "page"); else a.removeAttribute("aria-current");
  }
  try {
    if (path === "/new") await newView(params);
    else if (path.startsWith("/jobs/")) await jobView(decodeURIComponent(path.slice(6)));
    else await listView(params);
  } catch (err) {
    if (err && err.name === "AbortError") return;
    view().replaceChildren(h("div", { class: "problem" }, h("h2", {}, "Something went wrong"), h("p", {}, String(err && err.message || err))));
  }
}

document.addEventListener("DOMContentLoaded", () => {
  const input = document.getElementById("token");
  input.value = sessionStorage.getItem(TOKEN_KEY) || "";
  document.getElementById("token-form").addEventListener("submit", (e) => {
    e.preventDefault();
    const t = input.value.trim();
    if (t) sessionStorage.setItem(TOKEN_KEY, t); else sessionStorage.removeItem(TOKEN_KEY);
    kindsCache = null;
    route();
  });
  window.addEventListener("hashchange", route);
  route();
});

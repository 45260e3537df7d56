// tribod dashboard: plain JavaScript over the public API (/v1). Four views chosen by the URL
// hash: the job list (#/), the submit form (#/new), a job (#/jobs/<id>) and a comparison of
// finished jobs (#/compare?ids=a,b,c). The bearer token, when the server needs one, is kept in
// this tab's session storage and sent on every request; the live stream and the plots are
// fetched with it too (EventSource and <img> cannot send it). Interactive charts are drawn from
// the result JSON with uPlot (vendored: /assets/vendor/), the server's SVG plots stay below them.
"use strict";

const TOKEN_KEY = "tribod-token";
const ACTIVE = new Set(["queued", "running"]);
const view = () => document.getElementById("view");
let kindsCache = null;
let openapiCache = null;
let examplesCache = null;
const picked = new Set(); // jobs ticked on the list for a comparison (kept while the tab lives)
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


// The OpenAPI document (the new-job form is generated from its spec schemas).
async function openapi() {
  if (!openapiCache) {
    const { res, body } = await json("/openapi.json");
    if (!res.ok || !body) throw new Error("could not read /openapi.json (" + res.status + ")");
    openapiCache = body;
  }
  return openapiCache;
}

// The project's example specs (examples/*.json, embedded in the server): [{file, kind, label, spec}].
async function examples() {
  if (!examplesCache) {
    const res = await fetch("/assets/examples.json");
    examplesCache = res.ok ? await res.json() : [];
  }
  return examplesCache;
}

// JSON pointers (RFC 6901) and the values they point at.
function pointerOf(parts) {
  return parts.map((p) => "/" + String(p).replace(/~/g, "~0").replace(/\//g, "~1")).join("");
}

function partsOf(pointer) {
  return pointer.split("/").slice(1).map((p) => p.replace(/~1/g, "/").replace(/~0/g, "~"));
}

function getAt(value, parts) {
  let v = value;
  for (const p of parts) {
    if (v === null || typeof v !== "object") return undefined;
    v = v[p];
  }
  return v;
}

// Sets (or, with `undefined`, removes) the value at `parts`, creating the objects on the way;
// objects a removal leaves empty go too.
function setAt(root, parts, value) {
  const chain = [root];
  let o = root;
  for (const p of parts.slice(0, -1)) {
    if (o[p] === null || typeof o[p] !== "object" || Array.isArray(o[p])) o[p] = {};
    o = o[p];
    chain.push(o);
  }
  const last = parts[parts.length - 1];
  if (value !== undefined) {
    o[last] = value;
    return;
  }
  delete o[last];
  for (let i = chain.length - 1; i > 0 && Object.keys(chain[i]).length === 0; i--) delete chain[i - 1][parts[i - 1]];
}

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

// From which fraction of a multiple a value reads in it: films and pressures as tribologists
// quote them (0.3 µm, not 300 nm; 0.5 GPa), forces, powers and the rest from one (129.7 W, not
// 0.1297 kW).
const EARLY_MULTIPLES = new Set(["m", "Pa"]);

// The multiple of `unit` that suits a value of magnitude `v`: [factor, shown unit].
function multipleFor(v, unit) {
  let pick = [1, unit === "1" ? "" : (unit || "")];
  const steps = MULTIPLES[unit];
  if (steps && Number.isFinite(v) && v !== 0) {
    const from = EARLY_MULTIPLES.has(unit) ? 0.1 : 1;
    pick = steps[0];
    for (const s of steps) if (Math.abs(v) >= from * s[0]) pick = s;
  }
  return pick;
}

// A number to 4 significant figures (integers as they are).
function sig4(x) {
  if (!Number.isFinite(x)) return String(x);
  return Number.isInteger(x) && Math.abs(x) < 1e9 ? String(x) : String(Number(x.toPrecision(4)));
}

// A number with its unit, in the multiple that suits it (or `ref`, the largest magnitude of its
// quantity when several rows show it), to 4 significant figures.
function withUnit(v, unit, ref) {
  if (typeof v !== "number" || !Number.isFinite(v)) return fmt(v);
  const [factor, shown] = multipleFor(ref ?? v, unit);
  const text = sig4(v / factor);
  return shown ? text + " " + shown : text;
}

// The unit of a result field: the kind's `result_units`, else the result's own `units` (column
// → unit) for a field keyed by a quantity or a pointer (an optimisation's `objectives` and
// `variables`: `/cam/width` is column `cam.width`).
function unitIn(kind, result, path) {
  const unit = unitOf(kind, path);
  if (unit || !result || typeof result.units !== "object" || result.units === null) return unit;
  const leaf = path.split(".").pop();
  return result.units[leaf.replace(/^\//, "").split("/").join(".")] ?? "";
}

// One multiple per quantity over a result's rows ([[dotted path, value]]): a quantity is the
// field's name with its unit, so `best.friction_power` and `baseline.objectives.friction_power`
// read in the same multiple (as the compare view's rows do). Returns (path, value) => text.
function quantityFormatter(rows, kind, result) {
  const unitOf = (k, path) => unitIn(k, result, path);
  const keyOf = (path) => path.split(".").pop() + "|" + unitOf(kind, path);
  const largest = new Map();
  for (const [path, v] of rows) {
    if (typeof v !== "number" || !Number.isFinite(v)) continue;
    const key = keyOf(path);
    largest.set(key, Math.max(largest.get(key) || 0, Math.abs(v)));
  }
  return (path, v) => withUnit(v, unitOf(kind, path), largest.get(keyOf(path)) || undefined);
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

// The figures an engineer checks first: the kind's `key_figures` found in the result, else the
// result's `summary` and `checks`. [[dotted path, value]].
function keyRows(result, kind) {
  const rows = [];
  for (const pointer of (kind && kind.key_figures) || []) {
    const parts = partsOf(pointer);
    const v = getAt(result, parts);
    if (typeof v === "number" || typeof v === "boolean") rows.push([parts.join("."), v]);
  }
  if (rows.length) return rows;
  return summaryRows({ summary: result.summary, checks: result.checks }).filter(([, v]) => typeof v === "number" || typeof v === "boolean");
}

// ---- the job list -----------------------------------------------------------------------------

const COMPARE_MIN = 2;
const COMPARE_MAX = 8;

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
  // Finished jobs ticked here are compared side by side (#/compare?ids=…).
  const compare = h("button", { type: "button", id: "compare", disabled: true, onclick: () => {
    if (picked.size >= COMPARE_MIN && picked.size <= COMPARE_MAX) location.hash = "#/compare?ids=" + [...picked].join(",");
  } }, "Compare");
  const pickedNote = h("span", { class: "muted", id: "picked" });
  const clear = h("button", { type: "button", class: "secondary", id: "clear-picked", hidden: true, onclick: () => {
    picked.clear();
    body.querySelectorAll("input.pick").forEach((c) => { c.checked = false; });
    updatePicked();
  } }, "Clear");
  const updatePicked = () => {
    const n = picked.size;
    compare.disabled = n < COMPARE_MIN || n > COMPARE_MAX;
    clear.hidden = n === 0;
    pickedNote.textContent = n === 0 ? "tick " + COMPARE_MIN + "–" + COMPARE_MAX + " finished jobs to compare them"
      : n + " picked" + (n > COMPARE_MAX ? " (at most " + COMPARE_MAX + ")" : n < COMPARE_MIN ? " (at least " + COMPARE_MIN + ")" : "");
  };
  updatePicked();
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
      h("a", { href: "#/new" }, "Submit a job…"),
      h("span", { class: "compare-bar" }, compare, clear, pickedNote)),
    h("table", {},
      h("thead", {}, h("tr", {}, h("th", { scope: "col", class: "pick" }, h("span", { class: "visually-hidden" }, "Compare")),
        ["Job", "Kind", "Status", "Created", "Finished"].map((c) => h("th", { scope: "col" }, c)))),
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
      body.replaceChildren(h("tr", {}, h("td", { colspan: 6 }, (page && page.detail) || "could not list jobs (" + res.status + ")")));
      return;
    }
    if (page.jobs.length === 0) {
      body.replaceChildren(h("tr", {}, h("td", { colspan: 6, class: "muted" }, "No jobs yet. ", h("a", { href: "#/new" }, "Submit one."))));
    } else {
      body.replaceChildren(...page.jobs.map((j) => {
        const open = () => { location.hash = "#/jobs/" + j.id; };
        const label = j.label || shortId(j.id);
        const pick = j.status === "succeeded"
          ? h("input", { type: "checkbox", class: "pick", "data-id": j.id, checked: picked.has(j.id), "aria-label": "compare " + label,
            onclick: (e) => e.stopPropagation(), onkeydown: (e) => e.stopPropagation(),
            onchange: (e) => { if (e.target.checked) picked.add(j.id); else picked.delete(j.id); updatePicked(); } })
          : null;
        return h("tr", { class: "job", tabindex: 0, "data-id": j.id, onclick: open, onkeydown: (e) => { if (e.key === "Enter") open(); } },
          h("td", { class: "pick" }, pick),
          h("td", {}, h("a", { href: "#/jobs/" + j.id }, label)),
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

// Reading the OpenAPI document's JSON schemas: `$ref`s resolved, nullable wrappers
// (`oneOf [X, null]`, `type: [T, "null"]`) unwrapped, tagged unions found by their tag property.
function schemaReader(doc) {
  const schemas = (doc.components && doc.components.schemas) || {};
  const deref = (s) => {
    let out = s || {};
    for (let i = 0; out.$ref && i < 32; i++) {
      const { $ref, ...rest } = out;
      out = { ...(schemas[$ref.split("/").pop()] || {}), ...rest }; // the referring side's description wins
    }
    return out;
  };
  const isNull = (s) => {
    const d = deref(s);
    return d.type === "null" || (Array.isArray(d.type) && d.type.length === 1 && d.type[0] === "null");
  };
  const tagOf = (variant, key) => {
    const p = variant.properties && variant.properties[key] && deref(variant.properties[key]);
    if (!p) return undefined;
    if (p.const !== undefined) return p.const;
    return Array.isArray(p.enum) && p.enum.length === 1 ? p.enum[0] : undefined;
  };
  const discriminator = (variants) => {
    if (!variants.every((v) => v.properties)) return null;
    for (const key of Object.keys(variants[0].properties)) {
      const tags = variants.map((v) => tagOf(v, key));
      if (tags.every((t) => typeof t === "string") && new Set(tags).size === tags.length) return key;
    }
    return null;
  };
  // {type: number|integer|string|boolean|enum|object|union|json, nullable, description, …}
  const describe = (raw) => {
    let s = deref(raw);
    let nullable = false;
    for (let i = 0; Array.isArray(s.oneOf) && i < 8; i++) {
      const options = s.oneOf.filter((v) => !isNull(v));
      if (options.length < s.oneOf.length) nullable = true;
      if (options.length === 1) {
        const inner = deref(options[0]);
        s = { ...inner, description: s.description || inner.description };
        continue;
      }
      const variants = options.map(deref);
      if (variants.every((v) => Array.isArray(v.enum))) {
        return { type: "enum", values: variants.flatMap((v) => v.enum).filter((v) => v !== null), nullable, description: s.description };
      }
      const disc = discriminator(variants);
      if (disc) return { type: "union", disc, variants, tags: variants.map((v) => tagOf(v, disc)), nullable, description: s.description };
      return { type: "json", nullable, description: s.description };
    }
    let t = s.type;
    if (Array.isArray(t)) {
      if (t.includes("null")) nullable = true;
      t = t.find((x) => x !== "null");
    }
    const base = { nullable, description: s.description, minimum: s.minimum, maximum: s.maximum,
      exclusiveMinimum: s.exclusiveMinimum, exclusiveMaximum: s.exclusiveMaximum, default: s.default };
    if (Array.isArray(s.enum)) return { ...base, type: "enum", values: s.enum.filter((v) => v !== null) };
    if (t === "number" || t === "integer" || t === "boolean" || t === "string") return { ...base, type: t };
    if (s.properties && Object.keys(s.properties).length) return { ...base, type: "object", properties: s.properties, required: s.required || [] };
    return { ...base, type: "json", object: t === "object" };
  };
  return { deref, describe };
}

// The first sentence of a schema description (the whole one goes in the field's tooltip).
function firstSentence(text) {
  const flat = String(text || "").replace(/`/g, "").replace(/\s*\n\s*/g, " ").trim();
  const m = flat.match(/^(.+?\.)(\s|$)/);
  const one = m ? m[1] : flat;
  return one.length > 160 ? one.slice(0, 157) + "…" : one;
}

// A schema bound, short: 0.014, 5000, 1e-5, 1e+8.
function bound(v) {
  const a = Math.abs(v);
  if (a === 0 || (a >= 1e-3 && a < 1e5)) return String(Number(v.toPrecision(4)));
  return v.toExponential();
}

function rangeText(d) {
  const ok = (v) => typeof v === "number" && Number.isFinite(v) && Math.abs(v) < 1e15;
  const parts = [];
  if (ok(d.exclusiveMinimum)) parts.push("> " + bound(d.exclusiveMinimum));
  else if (ok(d.minimum)) parts.push("≥ " + bound(d.minimum));
  if (ok(d.exclusiveMaximum)) parts.push("< " + bound(d.exclusiveMaximum));
  else if (ok(d.maximum)) parts.push("≤ " + bound(d.maximum));
  return parts.join(", ");
}

// A form generated from a kind's spec schema, editing the same spec as the JSON editor: a field
// per property (description, range, enums as selects), nested objects as fieldsets (folded while
// absent), tagged unions as a select of the variant, arrays and free objects as JSON text.
// `onEdit(spec)` is called after each edit made in the form; `set(spec)` shows another spec.
function specForm(doc, schemaRef, onEdit) {
  const reader = schemaReader(doc);
  const root = reader.describe({ $ref: schemaRef });
  const container = h("div", { class: "spec-form", id: "spec-form", role: "group", "aria-label": "spec as a form" });
  const opened = new Set(); // optional sections the user unfolded
  let spec = {};

  const leaf = (parts, key, d, value, required) => {
    const pointer = pointerOf(parts);
    const attrs = { "data-pointer": pointer, "data-type": d.type, id: "f" + pointer.replace(/[^A-Za-z0-9_-]/g, "-"), name: pointer };
    let control;
    if (d.type === "number" || d.type === "integer") {
      const ok = (v) => typeof v === "number" && Number.isFinite(v) && Math.abs(v) < 1e15;
      control = h("input", { ...attrs, type: "number", step: d.type === "integer" ? 1 : "any",
        min: ok(d.minimum) ? d.minimum : null, max: ok(d.maximum) ? d.maximum : null,
        value: typeof value === "number" ? String(value) : null, placeholder: d.default !== undefined ? String(d.default) : null });
    } else if (d.type === "enum" || d.type === "boolean") {
      const values = d.type === "boolean" ? [true, false] : d.values.slice();
      if (value !== undefined && !values.some((v) => v === value)) values.push(value);
      control = h("select", attrs, h("option", { value: "" }, required ? "(choose)" : "(default)"),
        values.map((v) => h("option", { value: JSON.stringify(v) }, String(v))));
      control.value = value === undefined ? "" : JSON.stringify(value);
      control.dataset.type = "json-choice";
    } else if (d.type === "string") {
      control = h("input", { ...attrs, type: "text", value: typeof value === "string" ? value : null });
    } else {
      const text = value === undefined ? "" : JSON.stringify(value);
      control = d.object || (value && typeof value === "object" && !Array.isArray(value))
        ? h("textarea", { ...attrs, "data-type": "json", rows: 3, spellcheck: "false", placeholder: "JSON" }, text)
        : h("input", { ...attrs, "data-type": "json", type: "text", spellcheck: "false", value: text || null, placeholder: "JSON, e.g. [1, 2]" });
    }
    const hint = [firstSentence(d.description), rangeText(d)].filter(Boolean).join(" · ");
    return h("div", { class: "field", title: d.description || null },
      h("label", { for: attrs.id }, key, required ? h("span", { class: "req", title: "required" }, " *") : null),
      control,
      hint ? h("small", { class: "hint" }, hint) : null);
  };

  const fields = (parts, properties, required, value, skip) =>
    Object.entries(properties).filter(([k]) => k !== skip).map(([k, s]) =>
      node(parts.concat(k), k, reader.describe(s), value && typeof value === "object" ? value[k] : undefined, required.includes(k)));

  const group = (parts, key, d, value, required, inner) => {
    const pointer = pointerOf(parts);
    const present = value !== undefined && value !== null;
    const open = present || required || opened.has(pointer);
    const fold = h("button", { type: "button", class: "fold", "data-fold": pointer, "aria-expanded": open ? "true" : "false" },
      key, present || required ? null : h("span", { class: "muted" }, " (default)"));
    const hint = firstSentence(d.description);
    return h("fieldset", { class: "group", "data-pointer": pointer, title: d.description || null },
      h("legend", {}, fold),
      open ? [hint ? h("small", { class: "hint" }, hint) : null, inner()] : null);
  };

  const node = (parts, key, d, value, required) => {
    if (d.type === "object") {
      return group(parts, key, d, value, required, () => h("div", { class: "group-body" }, fields(parts, d.properties, d.required, value)));
    }
    if (d.type === "union") {
      return group(parts, key, d, value, required, () => {
        const pointer = pointerOf(parts);
        const present = value && typeof value === "object";
        let index = present ? d.tags.indexOf(value[d.disc]) : -1;
        if (present && index < 0) index = Math.max(0, d.variants.findIndex((v) => !(v.required || []).includes(d.disc)));
        const select = h("select", { "data-variant": pointer, "data-disc": d.disc, id: "v" + pointer.replace(/[^A-Za-z0-9_-]/g, "-"), "aria-label": key + " " + d.disc },
          h("option", { value: "" }, required ? "(choose)" : "(not set)"),
          d.tags.map((t) => h("option", { value: t }, t)));
        select.value = index >= 0 ? d.tags[index] : "";
        const variant = index >= 0 ? d.variants[index] : null;
        return h("div", { class: "group-body" },
          h("div", { class: "field" }, h("label", { for: select.id }, d.disc), select,
            variant && variant.description ? h("small", { class: "hint" }, firstSentence(variant.description)) : null),
          variant ? fields(parts, variant.properties, variant.required || [], value, d.disc) : null);
      });
    }
    return leaf(parts, key, d, value, required);
  };

  const render = () => {
    const scroll = container.scrollTop;
    const focused = document.activeElement && container.contains(document.activeElement) ? document.activeElement.id : null;
    if (root.type === "object") container.replaceChildren(...fields([], root.properties, root.required, spec));
    else container.replaceChildren(h("p", { class: "muted" }, "This kind's spec has no form: edit the JSON."));
    container.scrollTop = scroll;
    if (focused && document.getElementById(focused)) document.getElementById(focused).focus();
  };

  const read = (el) => {
    const raw = el.value;
    if (el.validity && el.validity.badInput) return { ok: false };
    if (raw.trim() === "") return { ok: true, value: undefined };
    const t = el.dataset.type;
    if (t === "number" || t === "integer") {
      const n = Number(raw);
      return Number.isFinite(n) ? { ok: true, value: n } : { ok: false };
    }
    if (t === "json" || t === "json-choice") {
      try { return { ok: true, value: JSON.parse(raw) }; } catch (_) { return { ok: false }; }
    }
    return { ok: true, value: raw };
  };

  container.addEventListener("input", (e) => {
    const el = e.target;
    if (el.dataset.variant !== undefined) {
      const parts = partsOf(el.dataset.variant);
      const d = reader.describe(nodeSchema(parts));
      const old = getAt(spec, parts);
      if (el.value === "") setAt(spec, parts, undefined);
      else {
        const variant = d.variants[d.tags.indexOf(el.value)];
        const next = { [el.dataset.disc]: el.value };
        for (const [k, v] of Object.entries(old && typeof old === "object" ? old : {})) {
          if (k !== el.dataset.disc && variant.properties[k]) next[k] = v;
        }
        setAt(spec, parts, next);
      }
      render();
      onEdit(spec);
      return;
    }
    if (el.dataset.pointer === undefined) return;
    const { ok, value } = read(el);
    el.classList.toggle("invalid", !ok);
    if (ok) el.removeAttribute("aria-invalid"); else el.setAttribute("aria-invalid", "true");
    if (!ok) return;
    setAt(spec, partsOf(el.dataset.pointer), value);
    onEdit(spec);
  });
  container.addEventListener("click", (e) => {
    const fold = e.target.closest("button.fold");
    if (!fold) return;
    const pointer = fold.dataset.fold;
    if (opened.has(pointer)) opened.delete(pointer); else opened.add(pointer);
    render();
  });

  // The schema of the spec value at `parts` (through the unions the spec chose).
  const nodeSchema = (parts) => {
    let s = { $ref: schemaRef };
    for (let i = 0; i < parts.length; i++) {
      const d = reader.describe(s);
      let props = d.properties;
      if (d.type === "union") {
        const v = getAt(spec, parts.slice(0, i));
        const index = v && typeof v === "object" ? d.tags.indexOf(v[d.disc]) : -1;
        props = (d.variants[index >= 0 ? index : 0] || {}).properties;
      }
      s = (props || {})[parts[i]] || {};
    }
    return s;
  };

  render();
  return {
    element: container,
    set(next) { spec = next; render(); },
  };
}

async function newView(params) {
  const root = view();
  const [all, exampleList] = await Promise.all([kinds(), examples().catch(() => [])]);
  const wanted = params.get("example");
  const startExample = exampleList.find((e) => e.file === wanted);
  const choice = startExample ? startExample.kind : params.get("kind") || "bearing_optimisation";
  const kindSelect = h("select", { id: "kind", name: "kind" }, all.map((k) => h("option", { value: k.name }, k.name)));
  kindSelect.value = all.some((k) => k.name === choice) ? choice : all[0].name;
  // Every example of the project, grouped by kind, described by its label.
  const byKind = new Map();
  for (const e of exampleList) {
    if (!byKind.has(e.kind)) byKind.set(e.kind, []);
    byKind.get(e.kind).push(e);
  }
  const exampleSelect = h("select", { id: "example", name: "example" },
    h("option", { value: "" }, exampleList.length ? "— " + exampleList.length + " examples —" : "— no examples —"),
    [...byKind.entries()].map(([kind, list]) => h("optgroup", { label: kind },
      list.map((e) => h("option", { value: e.file, title: e.file }, e.label || e.file.replace(/\.json$/, ""))))));
  const label = h("input", { id: "label", type: "text", name: "label", placeholder: "what this run is (optional)" });
  const editor = h("textarea", { id: "spec", name: "spec", spellcheck: "false", "aria-label": "job spec (JSON)" });
  const editorStatus = h("p", { class: "muted editor-status", id: "spec-status", "aria-live": "polite" });
  const description = h("p", { class: "muted", id: "kind-description" });
  const exampleNote = h("p", { class: "muted", id: "example-note" });
  const problems = h("div", { id: "problems", "aria-live": "polite" });
  const submit = h("button", { type: "submit", id: "submit" }, "Submit");
  const formPane = h("div", { class: "form-pane" }, h("p", { class: "muted" }, "Loading the form…"));
  let form = null;
  let doc = null;

  const pretty = (spec) => JSON.stringify(spec, null, 2);
  const buildForm = (spec) => {
    const k = all.find((x) => x.name === kindSelect.value);
    if (!doc || !k) return;
    form = specForm(doc, k.spec_schema, (edited) => {
      editor.value = pretty(edited);
      editorStatus.textContent = "";
    });
    form.set(JSON.parse(JSON.stringify(spec)));
    formPane.replaceChildren(form.element);
  };
  const show = (spec) => {
    editor.value = pretty(spec);
    editorStatus.textContent = "";
    problems.replaceChildren();
    buildForm(spec);
  };
  let exampleLabel = null; // the label an example filled in (cleared with the example)
  const fill = () => {
    const k = all.find((x) => x.name === kindSelect.value);
    description.textContent = k.description;
    exampleSelect.value = "";
    exampleNote.textContent = "";
    if (exampleLabel !== null && label.value === exampleLabel) label.value = "";
    exampleLabel = null;
    show(k.example);
  };
  const pick = (e) => {
    kindSelect.value = e.kind;
    const k = all.find((x) => x.name === e.kind);
    description.textContent = k ? k.description : "";
    exampleSelect.value = e.file;
    exampleNote.textContent = "Example examples/" + e.file + (e.label ? ": " + e.label : "");
    label.value = e.label || "";
    exampleLabel = label.value;
    show(e.spec);
  };
  kindSelect.addEventListener("change", fill);
  exampleSelect.addEventListener("change", () => {
    const e = exampleList.find((x) => x.file === exampleSelect.value);
    if (e) pick(e); else fill();
  });
  // The JSON editor drives the form while it parses; invalid JSON leaves the form as it was.
  editor.addEventListener("input", () => {
    let spec;
    try {
      spec = JSON.parse(editor.value);
    } catch (err) {
      editorStatus.textContent = "Not valid JSON (" + err.message + "): the form keeps the last valid spec.";
      return;
    }
    if (!spec || typeof spec !== "object" || Array.isArray(spec)) {
      editorStatus.textContent = "A spec is a JSON object: the form keeps the last valid spec.";
      return;
    }
    editorStatus.textContent = "";
    if (form) form.set(spec);
  });
  if (startExample) pick(startExample); else fill();

  const jobForm = h("form", { id: "job-form", novalidate: true, onsubmit: async (e) => {
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
  h("div", { class: "row" }, h("label", { class: "wide" }, "Start from an example", exampleSelect)),
  exampleNote,
  h("div", { class: "row" },
    h("label", {}, "Kind", kindSelect),
    h("label", {}, "Label", label),
    h("button", { type: "button", class: "secondary", onclick: fill }, "Reset to the kind's example"),
    submit),
  description,
  problems,
  h("div", { class: "editor" },
    h("section", { "aria-label": "form" }, h("h2", {}, "Form"), formPane),
    h("section", { "aria-label": "JSON" }, h("h2", {}, "JSON"), editor, editorStatus)));
  root.replaceChildren(h("h1", {}, "Submit a job"), jobForm);
  leave = () => {};

  // The form needs the schemas: built when the document arrives (the JSON editor works before).
  try {
    doc = await openapi();
  } catch (err) {
    formPane.replaceChildren(h("p", { class: "muted" }, "No form: " + err.message + ". Edit the JSON."));
    return;
  }
  let spec = null;
  try { spec = JSON.parse(editor.value); } catch (_) { spec = null; }
  if (spec && typeof spec === "object" && !Array.isArray(spec)) buildForm(spec);
  else formPane.replaceChildren(h("p", { class: "muted" }, "Fix the JSON to get the form."));
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

// ---- interactive charts (uPlot) ---------------------------------------------------------------

const PALETTE = ["#1f5fbf", "#d1495b", "#2a9d8f", "#e09f3e", "#7b4fa0", "#3d8c40", "#c15d9f", "#5a6b7d", "#8d6e2f", "#00a1c9"];
let liveCharts = []; // [{chart, box, height}] of the current view, resized with the window

function maxAbs(values) {
  let m = 0;
  for (const v of values) if (typeof v === "number" && Math.abs(v) > m) m = Math.abs(v);
  return m;
}

// 1 if strictly increasing, -1 if strictly decreasing, 0 otherwise.
function monotonic(values) {
  if (!values || values.length < 2 || values.some((v) => typeof v !== "number")) return 0;
  const dir = Math.sign(values[1] - values[0]);
  if (dir === 0) return 0;
  for (let i = 1; i < values.length; i++) if (Math.sign(values[i] - values[i - 1]) !== dir) return 0;
  return dir;
}

// The tables of a result that draw as curves: columnar tables (an object of equal-length
// numeric arrays, e.g. `series`) and row tables of flat objects (e.g. a sweep's `cases`, a wear
// history), against `angle_deg`, a sweep's first varied parameter or the first column — which
// must be strictly monotonic (2-D fields are not curves) and, but for a sweep, not a row counter.
// Only the kind's own tables (`tables` of GET /v1/kinds) when it lists them. The y columns are grouped by unit, and
// within a unit by magnitude (a film in nm is not drawn on the axis of a lift in mm).
// [{name, rows, x: {key, unit, values}, groups: [{unit, columns: [{key, unit, values}]}],
//   zero: [{key, unit, value, values}] (the columns that never change)}]
function curveTables(result, kind) {
  const out = [];
  const ownUnits = result && result.units && typeof result.units === "object" && !Array.isArray(result.units) ? result.units : null;
  // The kind's own tables (its CSV tables) when it lists them, else any table-shaped field.
  const listed = kind && Array.isArray(kind.tables) && kind.tables.length ? new Set(kind.tables) : null;
  const isSweep = Array.isArray(result && result.columns);
  for (const [name, table] of Object.entries(result || {})) {
    if (listed && !listed.has(name)) continue;
    let cols;
    let rows = false;
    if (Array.isArray(table)) {
      if (table.length < 2 || !table.every((r) => r && typeof r === "object" && !Array.isArray(r))) continue;
      rows = true;
      const keys = Object.keys(table[0]).filter((k) =>
        table.every((r) => r[k] === undefined || r[k] === null || typeof r[k] === "number") && table.some((r) => typeof r[k] === "number"));
      cols = keys.map((k) => [k, table.map((r) => (typeof r[k] === "number" ? r[k] : null))]);
    } else if (table && typeof table === "object") {
      const entries = Object.entries(table);
      if (entries.length < 2 || !entries.every(([, v]) => Array.isArray(v))) continue;
      const n = entries[0][1].length;
      if (n < 2 || entries.some(([, v]) => v.length !== n)) continue;
      cols = entries.filter(([, v]) => v.every((x) => x === null || typeof x === "number") && v.some((x) => typeof x === "number"));
    } else continue;
    if (cols.length < 2) continue;
    const byName = new Map(cols);
    const unit = (c) => (rows && ownUnits && typeof ownUnits[c] === "string" ? ownUnits[c] : unitOf(kind, rows ? name + ".0." + c : name + "." + c));
    const candidates = [];
    if (byName.has("angle_deg")) candidates.push("angle_deg");
    else {
      if (rows && isSweep) {
        const parameter = result.columns.find((c) => c !== "case" && byName.has(c));
        if (parameter) candidates.push(parameter);
      }
      candidates.push(cols[0][0]);
      if (byName.has("case")) candidates.push("case");
    }
    let xKey = null;
    let dir = 0;
    for (const c of candidates) {
      dir = monotonic(byName.get(c));
      if (dir) { xKey = c; break; }
    }
    // A row counter (run 1, 2, 3 …) is no abscissa, except for a sweep's cases.
    const xs = xKey ? byName.get(xKey) : null;
    if (!xKey || (rows && !isSweep && xs.every((v, i) => v === xs[0] + i))) continue;
    const order = (v) => (dir < 0 ? v.slice().reverse() : v);
    const ys = cols.filter(([k]) => k !== xKey && k !== "case" && !(xKey === "angle_deg" && k === "time"));
    // Columns that never change (zero, or a steady speed) are named, not drawn.
    const zero = ys.filter(([, v]) => v.every((x) => x === v[0])).map(([k, v]) => ({ key: k, unit: unit(k), value: v[0], values: v }));
    const byUnit = new Map();
    for (const [k, v] of ys) {
      if (zero.some((z) => z.key === k)) continue;
      const u = unit(k);
      if (!byUnit.has(u)) byUnit.set(u, []);
      byUnit.get(u).push({ key: k, unit: u, values: order(v), mag: maxAbs(v) });
    }
    const groups = [];
    for (const [u, list] of byUnit) {
      const clusters = [];
      for (const c of list.slice().sort((a, b) => b.mag - a.mag)) {
        const last = clusters[clusters.length - 1];
        if (last && c.mag >= last.top / 100) last.columns.push(c);
        else clusters.push({ top: c.mag, columns: [c] });
      }
      for (const cl of clusters) groups.push({ unit: u, columns: cl.columns.sort((a, b) => list.indexOf(a) - list.indexOf(b)) });
    }
    if (groups.length) out.push({ name, rows: byName.get(xKey).length, x: { key: xKey, unit: unit(xKey), values: order(byName.get(xKey)) }, groups, zero });
  }
  return out;
}

// One x column shared by curves sampled at different x: the union of the x values, gaps null.
function joinX(xs, ys) {
  const first = xs[0];
  if (xs.every((x) => x.length === first.length && x.every((v, i) => v === first[i]))) return [first, ys];
  const all = [...new Set(xs.flat())].sort((a, b) => a - b);
  const index = new Map(all.map((v, i) => [v, i]));
  return [all, ys.map((y, j) => {
    const joined = new Array(all.length).fill(null);
    xs[j].forEach((x, i) => { joined[index.get(x)] = y[i]; });
    return joined;
  })];
}

// A uPlot line chart in `box`: hover read-out in the legend, drag to zoom (x), double-click to
// reset, legend entries toggle their series. Values in SI, shown in the unit multiple that suits
// the largest of them (as withUnit does).
function lineChart(box, { x, series, unit, height = 280 }) {
  const [xf, xs] = multipleFor(maxAbs(x.values), x.unit);
  const [yf, ys] = multipleFor(Math.max(0, ...series.map((s) => maxAbs(s.values))), unit);
  const scale = (values, f) => values.map((v) => (typeof v === "number" ? v / f : null));
  const named = (name, shown) => (shown ? name + " (" + shown + ")" : name);
  const reading = (shown) => (u, v) => (v === null || v === undefined ? "–" : sig4(v) + (shown ? " " + shown : ""));
  const axisSize = (u, values) => Math.max(40, 10 + 7 * Math.max(0, ...(values || []).map((v) => String(v).length)));
  const opts = {
    width: Math.max(280, Math.floor(box.clientWidth || 560)),
    height,
    scales: { x: { time: false } },
    cursor: { drag: { x: true, y: false, setScale: true } },
    legend: { live: true },
    // Whether the chart is zoomed, on its box (data-zoomed): for a reader of the page, and tests.
    hooks: { setScale: [(u, key) => {
      if (key !== "x" || !u.data[0].length) return;
      const xs = u.data[0];
      box.dataset.zoomed = String(u.scales.x.min > xs[0] || u.scales.x.max < xs[xs.length - 1]);
    }] },
    axes: [
      { label: named(x.label || x.key, xs), stroke: "#5b6475", grid: { stroke: "#e6e8ec" } },
      { label: ys || (unit && unit !== "1" ? unit : undefined), stroke: "#5b6475", grid: { stroke: "#e6e8ec" }, size: axisSize },
    ],
    series: [
      { label: x.label || x.key, value: reading(xs) },
      ...series.map((s, i) => ({ label: s.label, stroke: s.color || PALETTE[i % PALETTE.length], width: 1.5, spanGaps: true, value: reading(ys) })),
    ],
  };
  const chart = new uPlot(opts, [scale(x.values, xf), ...series.map((s) => scale(s.values, yf))], box);
  box.dataset.series = String(series.length);
  box.dataset.unit = ys;
  liveCharts.push({ chart, box, height });
  return chart;
}

function dropCharts() {
  for (const c of liveCharts) c.chart.destroy();
  liveCharts = [];
}

let resizeFrame = 0;
window.addEventListener("resize", () => {
  cancelAnimationFrame(resizeFrame);
  resizeFrame = requestAnimationFrame(() => {
    for (const c of liveCharts) {
      const width = Math.max(280, Math.floor(c.box.clientWidth));
      if (width && Math.abs(width - c.chart.width) > 2) c.chart.setSize({ width, height: c.height });
    }
  });
});

// The result's curves, one <details> per table (the first open), one chart per unit group;
// charts are drawn when their table is first opened. Returns {element, draw} (draw once the
// element is in the page, whose width the charts take).
function chartsSection(result, kind) {
  const tables = curveTables(result, kind);
  if (!tables.length) return null;
  const section = h("section", { id: "charts", "aria-label": "interactive charts" },
    h("p", { class: "muted hint-line" }, "Hover for values · drag across a chart to zoom · double-click to reset · click a legend entry to hide or show its curve."));
  const drawers = [];
  tables.forEach((t, i) => {
    const grid = h("div", { class: "charts" });
    const details = h("details", { class: "chart-table", "data-table": t.name, open: i === 0 },
      h("summary", {}, h("strong", {}, t.name), h("span", { class: "muted" },
        " · " + t.rows + " rows against " + t.x.key + " · " + t.groups.length + (t.groups.length === 1 ? " chart" : " charts"))),
      grid,
      t.zero.length ? h("p", { class: "muted" }, "Constant throughout: " + t.zero.map((z) => z.key + " = " + withUnit(z.value, z.unit)).join(", ") + ".") : null);
    let drawn = false;
    const draw = () => {
      if (drawn || !details.open) return;
      drawn = true;
      for (const g of t.groups) {
        const box = h("div", { class: "chart-box" });
        grid.append(h("figure", { class: "chart", "data-table": t.name, "data-columns": g.columns.map((c) => c.key).join(",") },
          h("figcaption", {}, g.columns.map((c) => c.key).join(", ")), box));
        lineChart(box, { x: t.x, unit: g.unit, series: g.columns.map((c) => ({ label: c.key, values: c.values })) });
      }
    };
    details.addEventListener("toggle", draw);
    drawers.push(draw);
    section.append(details);
  });
  return { element: section, draw: () => drawers.forEach((d) => d()) };
}

// ---- one job ----------------------------------------------------------------------------------

async function jobView(id) {
  const root = view();
  const controller = new AbortController();
  const urls = [];
  let stopped = false;
  leave = () => { stopped = true; controller.abort(); urls.forEach((u) => URL.revokeObjectURL(u)); dropCharts(); };

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
      h("a", { href: "#/new?kind=" + encodeURIComponent(job.kind) }, "New " + job.kind + " job"),
      job.status === "succeeded" ? h("button", { type: "button", class: "secondary", id: "pick-job", "aria-pressed": picked.has(id) ? "true" : "false", onclick: (e) => {
        if (picked.has(id)) picked.delete(id); else picked.add(id);
        e.target.setAttribute("aria-pressed", picked.has(id) ? "true" : "false");
        e.target.textContent = picked.has(id) ? "Picked for comparison (" + picked.size + ")" : "Pick for comparison";
      } }, picked.has(id) ? "Picked for comparison (" + picked.size + ")" : "Pick for comparison") : null);
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
    const key = keyRows(result, kind);
    const shown = quantityFormatter(key.concat(summary), kind, result);
    const cell = ([k, v]) => h("tr", {}, h("td", {}, k),
      h("td", { class: typeof v === "number" ? "num" : (v === false ? "fail" : "") }, shown(k, v)));
    const charts = chartsSection(result, kind);
    // The server's SVG plots (the CLI's and the reports'), folded under the interactive charts.
    const server = h("details", { id: "server-plots", open: !charts },
      h("summary", {}, "Server plots (SVG, as in reports)"), plots);
    body.replaceChildren(
      ...(key.length ? [h("section", { class: "card", id: "key-results" }, h("h2", {}, "Key results"),
        h("table", { class: "summary" }, h("tbody", {}, key.map(cell))))] : []),
      h("h2", {}, "Plots"),
      ...(charts ? [charts.element] : []),
      server,
      h("h2", {}, "Downloads"), downloads,
      h("h2", {}, "All figures"),
      summary.length
        ? h("table", { class: "summary", id: "summary" }, h("tbody", {}, summary.map(cell)))
        : h("p", { class: "muted" }, "The result is all tables: see the CSV downloads."));
    if (charts) charts.draw();
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

// ---- comparing jobs ---------------------------------------------------------------------------

// #/compare?ids=a,b,c: the key results of 2–8 finished jobs side by side, and one curve they
// share overlaid (one series per job).
async function compareView(params) {
  const root = view();
  let stopped = false;
  leave = () => { stopped = true; dropCharts(); };
  const ids = [...new Set((params.get("ids") || "").split(",").map((s) => s.trim()).filter(Boolean))];
  root.replaceChildren(h("h1", {}, "Compare jobs"), h("p", { class: "muted" }, "Loading…"));
  if (ids.length < COMPARE_MIN || ids.length > COMPARE_MAX) {
    root.replaceChildren(h("h1", {}, "Compare jobs"), h("p", {},
      "A comparison takes " + COMPARE_MIN + " to " + COMPARE_MAX + " finished jobs: tick them on the ", h("a", { href: "#/" }, "job list"), "."));
    return;
  }
  const all = await kinds();
  const loaded = await Promise.all(ids.map(async (id) => {
    const { res, body: job } = await json("/v1/jobs/" + encodeURIComponent(id));
    if (!res.ok || !job) return { id, problem: (job && (job.detail || job.title)) || "HTTP " + res.status };
    if (job.status !== "succeeded") return { id, job, problem: "is " + job.status + ", not finished" };
    const { res: rr, body: result } = await json("/v1/jobs/" + encodeURIComponent(id) + "/result");
    if (!rr.ok || !result) return { id, job, problem: "has no result (" + rr.status + ")" };
    return { id, job, result, kind: all.find((k) => k.name === job.kind) };
  }));
  if (stopped) return;
  const jobs = loaded.filter((j) => j.result);
  const left = loaded.filter((j) => !j.result);
  // Column names: the labels, told apart by the short id where two are the same.
  const labels = jobs.map((j) => j.job.label || shortId(j.id));
  jobs.forEach((j, i) => { j.name = labels.filter((l) => l === labels[i]).length > 1 ? labels[i] + " (" + shortId(j.id) + ")" : labels[i]; });

  const skipped = left.length
    ? h("div", { class: "warnings", id: "compare-skipped" }, h("h2", {}, "Left out"),
      h("ul", {}, left.map((j) => h("li", {}, h("a", { href: "#/jobs/" + j.id }, (j.job && j.job.label) || shortId(j.id)), " ", j.problem))))
    : null;
  if (jobs.length < 2) {
    root.replaceChildren(...[h("h1", {}, "Compare jobs"), skipped, h("p", {}, "Fewer than two finished jobs to compare. ", h("a", { href: "#/" }, "Back to the jobs."))].filter(Boolean));
    return;
  }

  // Key results side by side: the union of the jobs' key figures and summary numbers, each row
  // in one unit multiple.
  const rows = new Map(); // dotted path -> unit
  for (const j of jobs) {
    const numbers = keyRows(j.result, j.kind).concat(summaryRows({ summary: j.result.summary }))
      .filter(([, v]) => typeof v === "number" || typeof v === "boolean");
    for (const [path] of numbers) {
      const unit = unitOf(j.kind, path);
      if (!rows.has(path) || (!rows.get(path) && unit)) rows.set(path, unit);
    }
  }
  const table = h("table", { class: "summary compare", id: "compare-table" },
    h("thead", {}, h("tr", {}, h("th", { scope: "col" }, "Figure"), h("th", { scope: "col" }, "Unit"),
      jobs.map((j) => h("th", { scope: "col", "data-id": j.id }, h("a", { href: "#/jobs/" + j.id }, j.name), h("div", { class: "muted" }, j.job.kind))))),
    h("tbody", {}, [...rows.entries()].map(([path, unit]) => {
      const values = jobs.map((j) => getAt(j.result, path.split(".")));
      const [factor, shown] = multipleFor(maxAbs(values.filter((v) => typeof v === "number")), unit);
      return h("tr", { "data-path": path }, h("td", {}, path), h("td", { class: "unit" }, shown),
        values.map((v) => h("td", { class: typeof v === "number" ? "num" : v === false ? "fail" : "muted" },
          typeof v === "number" ? sig4(v / factor) : v === undefined ? "–" : fmt(v))));
    })));

  // The curves every job has (same table, column and x), one chosen at a time.
  const perJob = jobs.map((j) => {
    const curves = new Map();
    for (const t of curveTables(j.result, j.kind)) {
      for (const c of t.groups.flatMap((g) => g.columns).concat(t.zero)) curves.set(t.name + "." + c.key, { x: t.x, unit: c.unit, values: c.values });
    }
    return curves;
  });
  const shared = [...perJob[0].keys()].filter((k) => perJob.every((m) => m.has(k) && m.get(k).x.key === perJob[0].get(k).x.key));
  const prefer = [/(^|\.)film_min$/, /film/, /pressure/];
  const preferred = prefer.map((re) => shared.find((k) => re.test(k))).find(Boolean) || shared[0];
  const box = h("div", { class: "chart-box", id: "compare-chart" });
  const select = h("select", { id: "compare-column", name: "column" },
    shared.map((k) => h("option", { value: k }, k + (perJob[0].get(k).unit && perJob[0].get(k).unit !== "1" ? " (" + perJob[0].get(k).unit + ")" : ""))));
  const draw = () => {
    dropCharts();
    box.replaceChildren();
    const key = select.value;
    const curves = perJob.map((m) => m.get(key));
    const [x, ys] = joinX(curves.map((c) => c.x.values), curves.map((c) => c.values));
    lineChart(box, { x: { key: curves[0].x.key, unit: curves[0].x.unit, values: x }, unit: curves[0].unit, height: 360,
      series: jobs.map((j, i) => ({ label: j.name, values: ys[i] })) });
  };
  select.addEventListener("change", draw);

  root.replaceChildren(...[
    h("h1", {}, "Compare ", jobs.length, " jobs"),
    h("p", { class: "muted" }, "This page's address reopens the same comparison. ", h("a", { href: "#/" }, "Pick other jobs on the list.")),
    skipped,
    h("h2", {}, "Key results"),
    h("div", { class: "scroll" }, table),
    h("h2", {}, "Curves"),
    shared.length
      ? [h("div", { class: "filters" }, h("label", {}, "Column", select)),
        h("p", { class: "muted hint-line" }, "Hover for values · drag to zoom · double-click to reset · click a job in the legend to hide or show it."),
        h("figure", { class: "chart wide" }, box)]
      : h("p", { class: "muted", id: "compare-no-curves" }, "These jobs share no curve (no column of the same table against the same x)."),
  ].flat().filter(Boolean));
  if (shared.length) {
    select.value = preferred;
    draw();
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
  for (const [id, on] of [["nav-jobs", path === "/" || path === "/compare"], ["nav-new", path === "/new"]]) {
    const a = document.getElementById(id);
    if (on) a.setAttribute("aria-current", "page"); else a.removeAttribute("aria-current");
  }
  try {
    if (path === "/new") await newView(params);
    else if (path.startsWith("/jobs/")) await jobView(decodeURIComponent(path.slice(6)));
    else if (path === "/compare") await compareView(params);
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
    openapiCache = null;
    route();
  });
  window.addEventListener("hashchange", route);
  route();
});

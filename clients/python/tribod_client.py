"""A small client for the tribod HTTP API, for pipelines and notebooks.

Standard library only (urllib, json). Python 3.8 or later.

    from tribod_client import Client
    c = Client("http://127.0.0.1:8080")             # token=... when the server has --api-token
    job = c.submit("hertz", {"contact": "line", "load": 5000, "length": 0.014,
                             "body_1": {"shape": "cylinder", "radius": 0.0255},
                             "body_2": {"shape": "cylinder", "radius": 0.02}})
    job = c.wait(job["id"], timeout=60)
    result = c.result(job["id"])
    for pointer, value, unit in c.key_results(job["kind"], result):
        print(pointer, format_quantity(value, unit))

Every number in a result is SI; `units(kind)` gives each field's unit (`GET /v1/kinds`
`result_units`: JSON pointer -> unit, `*` for any row index, `1` for a pure number).
Errors of the API (application/problem+json) raise `TribodError` with its `code`, `detail` and
`errors` ([{path, message}]).
"""

import json
import os
import re
import time
import urllib.error
import urllib.parse
import urllib.request

__all__ = ["Client", "TribodError", "JobFailed", "format_quantity", "pointer_get"]

FINISHED = {"succeeded", "failed", "canceled"}


class TribodError(Exception):
    """An error answer of the API (RFC 9457 problem), or a transport failure (status 0)."""

    def __init__(self, status, problem=None, message=None):
        self.status = status
        self.problem = problem or {}
        self.code = self.problem.get("code")
        self.detail = self.problem.get("detail") or message or ""
        self.errors = self.problem.get("errors") or []
        if status == 0:
            text = self.detail
        else:
            text = f"{status} {self.code}: {self.detail}" if self.code else f"{status}: {self.detail}"
        for e in self.errors:
            text += f"\n  {e.get('path')}: {e.get('message')}"
        super().__init__(text)


class JobFailed(TribodError):
    """A job that ended `failed` or `canceled`; `job` is the job, `problem` its stored error."""

    def __init__(self, job):
        self.job = job
        error = job.get("error") or {"code": job.get("status"), "detail": f"job {job.get('id')} {job.get('status')}"}
        super().__init__(error.get("status", 0), error)


class Client:
    """One tribod server. `token`: the bearer token of a server started with `--api-token`."""

    def __init__(self, base_url="http://127.0.0.1:8080", token=None, timeout=60.0):
        self.base_url = base_url.rstrip("/")
        self.token = token
        self.timeout = timeout
        self._kinds = None

    # ---- HTTP -------------------------------------------------------------------------------

    def _request(self, method, path, body=None, headers=None, query=None, timeout=None):
        url = self.base_url + path
        if query:
            url += "?" + urllib.parse.urlencode({k: v for k, v in query.items() if v is not None})
        data = None
        hdrs = {"Accept": "application/json"}
        if body is not None:
            data = json.dumps(body).encode("utf-8")
            hdrs["Content-Type"] = "application/json"
        if self.token:
            hdrs["Authorization"] = f"Bearer {self.token}"
        hdrs.update(headers or {})
        req = urllib.request.Request(url, data=data, headers=hdrs, method=method)
        try:
            with urllib.request.urlopen(req, timeout=timeout or self.timeout) as resp:
                return resp.status, dict(resp.headers), resp.read()
        except urllib.error.HTTPError as e:
            raw = e.read()
            try:
                problem = json.loads(raw.decode("utf-8"))
            except ValueError:
                problem = {"detail": raw.decode("utf-8", "replace")}
            err = TribodError(e.code, problem)
            err.headers = dict(e.headers or {})
            raise err from None
        except urllib.error.URLError as e:
            raise TribodError(0, message=f"cannot reach {self.base_url}: {e.reason}") from None

    def _json(self, method, path, **kw):
        _, _, raw = self._request(method, path, **kw)
        return json.loads(raw.decode("utf-8")) if raw else None

    # ---- kinds and units --------------------------------------------------------------------

    def kinds(self, refresh=False):
        """Every kind (`GET /v1/kinds`): name, description, example, outputs, tables, units."""
        if self._kinds is None or refresh:
            self._kinds = self._json("GET", "/v1/kinds")["kinds"]
        return self._kinds

    def kind(self, name):
        for k in self.kinds():
            if k["name"] == name:
                return k
        raise TribodError(422, {"code": "unknown_kind", "detail": f"no kind {name!r}"})

    def units(self, kind):
        """The unit of every result field of `kind`: {JSON pointer: unit}."""
        return dict(self.kind(kind).get("result_units") or {})

    def unit_of(self, kind, pointer):
        """The unit at one pointer of a result (row indices match `*`); None if not numeric."""
        units = self.units(kind)
        if pointer in units:
            return units[pointer]
        return units.get(re.sub(r"/\d+(?=/|$)", "/*", pointer))

    def key_figures(self, kind):
        """The pointers an engineer checks first (`GET /v1/kinds` `key_figures`)."""
        return list(self.kind(kind).get("key_figures") or [])

    # ---- jobs -------------------------------------------------------------------------------

    def submit(self, kind, spec, label=None, wait=None, strict=False, fresh=False,
               idempotency_key=None, retries=3):
        """Submit a job; returns the job (`202`, or `200` when it finished within `wait` s).

        `strict=True` refuses a spec with warnings (422); `fresh=True` re-solves an identical
        spec instead of reusing its job. With an `idempotency_key` a `503` (full queue, storage
        unavailable) or a lost connection is retried up to `retries` times after `Retry-After`:
        the server answers the same job to the same request under the same key."""
        body = {"kind": kind, "spec": spec}
        if label is not None:
            body["label"] = label
        headers = {}
        if wait:
            headers["Prefer"] = f"wait={int(wait)}"
        if idempotency_key:
            headers["Idempotency-Key"] = idempotency_key
        query = {"strict": "true" if strict else None, "fresh": "true" if fresh else None}
        timeout = self.timeout + (wait or 0)
        attempt = 0
        while True:
            try:
                return self._json("POST", "/v1/jobs", body=body, headers=headers, query=query, timeout=timeout)
            except TribodError as e:
                attempt += 1
                if not idempotency_key or attempt > retries or e.status not in (0, 503):
                    raise
                time.sleep(float(getattr(e, "headers", {}).get("Retry-After", 1)))

    def submit_file(self, path, **kw):
        """Submit a job file of `examples/` (`{"kind", "spec", "label"?}`)."""
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
        kw.setdefault("label", doc.get("label"))
        return self.submit(doc["kind"], doc["spec"], **kw)

    def job(self, job_id):
        """One job: status, progress, timings, spec, `warnings`, `estimate`, error."""
        return self._json("GET", f"/v1/jobs/{job_id}")

    def jobs(self, status=None, kind=None, limit=100):
        """Jobs, newest first, page by page (`status` may be a list)."""
        if isinstance(status, (list, tuple)):
            status = ",".join(status)
        after = None
        while True:
            page = self._json("GET", "/v1/jobs", query={"status": status, "kind": kind, "limit": limit, "after": after})
            yield from page["jobs"]
            after = page.get("next")
            if not after:
                return

    def wait(self, job_id, timeout=600.0, poll=0.2):
        """Wait until the job has ended; return it. Raises `JobFailed` when it failed or was
        canceled, `TimeoutError` after `timeout` seconds."""
        deadline = time.monotonic() + timeout
        while True:
            job = self.job(job_id)
            if job["status"] == "succeeded":
                return job
            if job["status"] in FINISHED:
                raise JobFailed(job)
            if time.monotonic() >= deadline:
                raise TimeoutError(f"job {job_id} still {job['status']} after {timeout} s")
            time.sleep(poll)
            poll = min(poll * 1.5, 2.0)

    def cancel(self, job_id):
        """Cancel a queued or running job, or delete a finished one."""
        self._request("DELETE", f"/v1/jobs/{job_id}")

    # ---- results ----------------------------------------------------------------------------

    def result(self, job_id):
        """The result JSON (SI units; `meta` has the solver version and wall time)."""
        return self._json("GET", f"/v1/jobs/{job_id}/result")

    def csv(self, job_id, table=None):
        """One table of the result as CSV text (default: the kind's first table); the header
        carries units: `film_min [m]`."""
        _, _, raw = self._request("GET", f"/v1/jobs/{job_id}/result", headers={"Accept": "text/csv"},
                                  query={"format": "csv", "table": table})
        return raw.decode("utf-8")

    def plots(self, job_id):
        """The plots of a finished job: [{name, title, href}]."""
        return self._json("GET", f"/v1/jobs/{job_id}/plots")["plots"]

    def plot(self, job_id, name):
        """One plot as SVG bytes (by its `href` in the plot list)."""
        for p in self.plots(job_id):
            if p["name"] == name:
                _, _, raw = self._request("GET", p["href"], headers={"Accept": "image/svg+xml"})
                return raw
        raise TribodError(404, {"code": "plot_not_found", "detail": f"job {job_id} has no plot {name!r}"})

    def key_results(self, kind, result):
        """(pointer, value, unit) of the figures an engineer reads first: every number of the
        result's `summary` (and a bearing's `checks`), as the dashboard's *Key results* card;
        for a result without them, the kind's `key_figures`."""
        rows = []

        def walk(value, pointer):
            if isinstance(value, dict):
                for k, v in value.items():
                    walk(v, f"{pointer}/{k}")
            elif isinstance(value, (int, float)):  # bool too: a check's pass
                rows.append(pointer)

        for part in ("summary", "checks"):
            if isinstance(result.get(part), dict):
                walk(result[part], f"/{part}")
        if not rows:
            rows = [p for p in self.key_figures(kind) if pointer_get(result, p) is not None]
        return [(p, pointer_get(result, p), self.unit_of(kind, p)) for p in rows]


# ---- helpers ---------------------------------------------------------------------------------

def pointer_get(doc, pointer):
    """The value at a JSON pointer (RFC 6901), or None."""
    if pointer in ("", "/"):
        return doc
    for part in pointer.lstrip("/").split("/"):
        part = part.replace("~1", "/").replace("~0", "~")
        if isinstance(doc, list):
            try:
                doc = doc[int(part)]
            except (ValueError, IndexError):
                return None
        elif isinstance(doc, dict):
            if part not in doc:
                return None
            doc = doc[part]
        else:
            return None
    return doc


_MULTIPLES = {  # the dashboard's engineering multiples
    "m": [(1e-9, "nm"), (1e-6, "µm"), (1e-3, "mm"), (1, "m")],
    "Pa": [(1, "Pa"), (1e3, "kPa"), (1e6, "MPa"), (1e9, "GPa")],
    "N": [(1, "N"), (1e3, "kN"), (1e6, "MN")],
    "W": [(1e-3, "mW"), (1, "W"), (1e3, "kW")],
    "N·m": [(1e-3, "N·mm"), (1, "N·m")],
    "Pa·s": [(1e-3, "mPa·s"), (1, "Pa·s")],
    "m³/s": [(1e-9, "mm³/s"), (1e-6, "cm³/s"), (1e-3, "L/s"), (1, "m³/s")],
    "s": [(1e-6, "µs"), (1e-3, "ms"), (1, "s")],
}


def format_quantity(value, unit):
    """`0.00021 m` -> `210.2 µm`: an SI value in the multiple that suits it, 4 significant
    figures; pure numbers (`1`) without a unit."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return str(value)
    shown, factor = ("" if unit in (None, "1") else unit), 1.0
    steps = _MULTIPLES.get(unit)
    if steps and value != 0:
        factor, shown = steps[0]
        for f, name in steps:
            if abs(value) >= 0.1 * f:
                factor, shown = f, name
    x = value / factor
    text = str(int(x)) if float(x).is_integer() and abs(x) < 1e9 else f"{x:.4g}"
    return f"{text} {shown}" if shown else text


def from_env():
    """A client for `TRIBOD_URL` (default http://127.0.0.1:8080) and `TRIBOD_API_TOKEN`."""
    return Client(os.environ.get("TRIBOD_URL", "http://127.0.0.1:8080"), token=os.environ.get("TRIBOD_API_TOKEN"))

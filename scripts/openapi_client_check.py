#!/usr/bin/env python3
"""Submit one job of every kind through a client generated from openapi/openapi.json.

Proof that the OpenAPI document is usable by a standard generator (issue 10, defect 8): the typed
request model of each kind is built from the kind's example, sent with the generated
`submit_job`, and the job is followed with the generated `get_job` until it finishes.

Usage: openapi_client_check.py <generated client parent dir> <server base URL>
(run by scripts/openapi_checks.sh, which generates the client and starts the server).
"""
import importlib
import sys
import time

sys.path.insert(0, sys.argv[1])
base = sys.argv[2]

from tribod_client import Client  # noqa: E402
from tribod_client.api.jobs import get_job, submit_job  # noqa: E402
from tribod_client.api.kinds import list_kinds  # noqa: E402
from tribod_client.models import JobView  # noqa: E402

client = Client(base_url=base, raise_on_unexpected_status=True, timeout=60.0)
kinds = list_kinds.sync(client=client)
failures = []
for kind in kinds.kinds:
    if kind.name.startswith("test_"):
        continue
    camel = "".join(w.capitalize() for w in kind.name.split("_"))
    module = importlib.import_module(f"tribod_client.models.{kind.name}_job_request")
    request_type = getattr(module, f"{camel}JobRequest")
    example = kind.example.to_dict() if hasattr(kind.example, "to_dict") else kind.example
    request = request_type.from_dict({"kind": kind.name, "spec": example, "label": "generated client"})
    response = submit_job.sync_detailed(client=client, body=request, fresh=True)
    job = response.parsed
    if not isinstance(job, JobView):
        failures.append(f"{kind.name}: submit answered {response.status_code}: {response.content[:300]!r}")
        continue
    deadline = time.time() + 300
    while job.status.value in ("queued", "running") and time.time() < deadline:
        time.sleep(0.2)
        job = get_job.sync(client=client, id=job.id)
    print(f"{kind.name:22s} {response.status_code} -> {job.status.value}")
    if job.status.value != "succeeded":
        failures.append(f"{kind.name}: finished {job.status.value}")
if failures:
    print("\n".join(failures), file=sys.stderr)
    sys.exit(1)
print(f"generated client: {len([k for k in kinds.kinds if not k.name.startswith('test_')])} kinds submitted, all succeeded")

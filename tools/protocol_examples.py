"""Rewrite the example answers of docs/protocol.md with the tool's own answers.

Each `-> ` line after a request line becomes `aecurve batch`'s answer to that request, arrays
longer than four items cut to three and "...", numbers to ten digits. A request line that is
not JSON keeps its documented answer. The unit test `protocol_md_examples_are_valid_by_the_schema`
checks both lines against the schema; this script only keeps the numbers current.

    AECURVE=target/release/aecurve python3 tools/protocol_examples.py
"""

import json
import os
import re
import subprocess
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
AE = os.environ.get("AECURVE") or str(REPO / "target" / "release" / "aecurve")
DOC = REPO / "docs" / "protocol.md"
doc = DOC.read_text().split("\n")


def run(req):
    """The first answer line of `aecurve batch` to one request line."""
    out = subprocess.run([AE, 'batch'], input=req + '\n', capture_output=True, text=True).stdout
    return json.loads(out.splitlines()[0])


def num(v):
    """A float to ten significant digits."""
    if isinstance(v, float):
        s = '%.10g' % v
        return float(s)
    return v


def abbreviate(v):
    """Arrays over four items cut to three and '...', numbers rounded, all the way down."""
    if isinstance(v, list):
        keep = v if len(v) <= 4 else v[:3]
        out = [abbreviate(x) for x in keep]
        if len(v) > 4:
            out.append('...')
        return out
    if isinstance(v, dict):
        return {k: abbreviate(x) for k, x in v.items()}
    return num(v)


for i in range(1, len(doc)):
    if not doc[i].startswith('-> '):
        continue
    req = doc[i - 1]
    try:
        json.loads(req)
    except ValueError:
        continue  # deliberately not JSON: its documented answer stays
    ans = run(req)
    if not ans['ok'] and ans['error']['kind'] == 'unknown_op':
        ans['error']['message'] = re.sub(r'known: (.{40}).*', r'known: \1...', ans['error']['message'])
    a = abbreviate(ans)
    head = {k: a[k] for k in ('id', 'ok', 'result', 'error') if k in a}
    body = {k: (json.loads(json.dumps(v, sort_keys=True))) for k, v in head.items()}
    doc[i] = '-> ' + json.dumps(body, ensure_ascii=False).replace(': NaN', ': null')
DOC.write_text("\n".join(doc))

// The server: every number the page shows comes from here (POST /api: the batch protocol;
// /api/region: the shaded regions; /api/export: files). Server-Timing is collected per op.

export class ApiError extends Error {
  constructor(e) {
    super(`${e.kind}: ${e.message}`);
    this.kind = e.kind;
  }
}

export const timing = {
  last: 0,
  max: 0,
  perOp: {}, // every server time per op (and per region kind), in order
};

export async function post(path, body) {
  const what = body.op || (body.kind ? `region.${body.kind}` : path);
  const r = await fetch(path, {
    method: 'POST',
    headers: { 'content-type': 'application/json' },
    body: JSON.stringify(body),
  });
  const st = r.headers.get('server-timing');
  const m = st && /dur=([\d.]+)/.exec(st);
  if (m) {
    timing.last = +m[1];
    timing.max = Math.max(timing.max, timing.last);
    (timing.perOp[what] = timing.perOp[what] || []).push(timing.last);
  }
  return r;
}

// One protocol request; its result, or an ApiError.
export async function api(req) {
  const v = await (await post('/api', req)).json();
  if (!v.ok) throw new ApiError(v.error);
  return v.result;
}

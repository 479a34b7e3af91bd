// The side panel's text: numbers, the verdict, the status line.

export const $ = (id) => document.getElementById(id);

export function fmt(x, d = 4) {
  if (typeof x !== 'number') return String(x);
  if (Number.isInteger(x) && Math.abs(x) < 1e9) return String(x);
  const a = Math.abs(x);
  return a >= 1e4 || a < 1e-3 ? x.toExponential(2) : x.toFixed(d);
}

// rows: [key, label, value]
export function setNumbers(rows) {
  const t = $('numbers');
  t.innerHTML = '';
  for (const [key, label, value] of rows) {
    const tr = document.createElement('tr');
    tr.innerHTML = `<td>${label}</td><td id="n-${key}">${typeof value === 'number' ? fmt(value) : value}</td>`;
    t.appendChild(tr);
  }
}

export function setVerdict(text, good) {
  const v = $('verdict');
  v.textContent = text;
  v.className = good === undefined ? '' : good ? 'yes' : 'no';
}

export function setStatus(text, error) {
  const s = $('status');
  s.textContent = text;
  s.className = error ? 'error' : '';
}

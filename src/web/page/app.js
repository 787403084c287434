/* The teaching page: controls, URL state and drawing.  Every field value,
 * gradient, jet, order and bound comes from dflab's C library through the
 * WebAssembly API of src/web/dflweb.h; this file only maps numbers to
 * pixels and text. */
'use strict';

const JOINS = ['requiv', 'rconj', 'requiv_corrected'];          /* rfunc/join.h order */
const JOIN_LABELS = ['R-equivalence (eq. 6)', 'R-conjunction (eq. 7)', 'corrected (eq. 20)'];
const TRIMS = ['disk', 'disk_smooth', 'strip', 'strip_smooth']; /* rfunc/segment.h order */
/* bs04_normalization.ini's polyline. */
const NORM_V = [0.05, 0.9, 0.3, 0.1, 0.5, 0.6, 0.72, 0.12, 0.95, 0.85];
/* Control points of configs/shapes/W.ini and S.ini (order 4, clamped uniform knots). */
const SHAPES = {
  W: [0.05, 0.95, 0.2, 0.05, 0.35, 0.05, 0.5, 0.75, 0.65, 0.05, 0.8, 0.05, 0.95, 0.95],
  S: [0.85, 0.85, 0.6, 1.0, 0.1, 0.95, 0.1, 0.6, 0.5, 0.5, 0.9, 0.4, 0.9, 0.05, 0.4, 0.0, 0.15, 0.15],
};
const N = 256;

/* The state, in the order it is written to the URL; defaults below. */
const DEFAULTS = {
  alpha: 120, p: 2, join: 'requiv', trim: 'disk', view: 'u',
  np: 4, njoin: 'requiv', ntrim: 'disk', nseg: 1, nt: 0.5, nside: 1,
  shape: 'W', eps: '0.02', bp: 2, cp: '',
};
const state = Object.assign({}, DEFAULTS);

function parseHash(h) {
  const s = Object.assign({}, DEFAULTS);
  for (const kv of h.replace(/^#/, '').split('&')) {
    if (!kv) continue;
    const i = kv.indexOf('=');
    const k = decodeURIComponent(i < 0 ? kv : kv.slice(0, i));
    const v = decodeURIComponent(i < 0 ? '' : kv.slice(i + 1));
    if (!(k in DEFAULTS)) continue;
    s[k] = typeof DEFAULTS[k] === 'number' ? Number(v) : v;
    if (typeof DEFAULTS[k] === 'number' && !Number.isFinite(s[k])) s[k] = DEFAULTS[k];
  }
  const clampInt = (x, lo, hi) => Math.min(hi, Math.max(lo, Math.round(x)));
  s.alpha = clampInt(s.alpha, 10, 350);
  s.p = clampInt(s.p, 1, 12); s.np = clampInt(s.np, 1, 12); s.bp = clampInt(s.bp, 1, 12);
  s.nseg = clampInt(s.nseg, 0, 3);
  s.nt = Math.min(0.95, Math.max(0.05, s.nt));
  s.nside = s.nside < 0 ? -1 : 1;
  if (!JOINS.includes(s.join)) s.join = DEFAULTS.join;
  if (!JOINS.includes(s.njoin)) s.njoin = DEFAULTS.njoin;
  if (!TRIMS.includes(s.trim) && s.trim !== 'exact') s.trim = DEFAULTS.trim;
  if (!['disk', 'disk_smooth', 'strip'].includes(s.ntrim)) s.ntrim = DEFAULTS.ntrim;
  if (!['u', 'err'].includes(s.view)) s.view = DEFAULTS.view;
  if (!(s.shape in SHAPES)) s.shape = DEFAULTS.shape;
  if (!['0.05', '0.02', '0.01', '0.005', '0.002', '0.001'].includes(s.eps)) s.eps = DEFAULTS.eps;
  if (s.cp) {
    const c = s.cp.split(',').map(Number);
    if (c.length !== SHAPES[s.shape].length || !c.every(Number.isFinite)) s.cp = '';
  }
  return s;
}

/* Only what differs from the defaults, in DEFAULTS' order. */
function formatHash(s) {
  const parts = [];
  for (const k of Object.keys(DEFAULTS))
    if (String(s[k]) !== String(DEFAULTS[k])) parts.push(k + '=' + encodeURIComponent(String(s[k])));
  return parts.length ? '#' + parts.join('&') : '';
}

/* ---- the library ---------------------------------------------------------- */

let M = null;           /* the emscripten module */
const scenes = {};      /* dflw_scene pointers per panel */
let buf = null;         /* scratch in the wasm heap */
const BUF_DOUBLES = 1024;

function heap64() { return M.HEAPF64; }
function setDoubles(ptr, arr) { heap64().set(arr, ptr >> 3); }
function getDoubles(ptr, n) { return Array.from(heap64().subarray(ptr >> 3, (ptr >> 3) + n)); }
function errorOf(sc) { return M.UTF8ToString(M._dflw_scene_error(sc)); }

class Grid {
  constructor(n) {
    this.n = n;
    this.ptr = M._malloc(3 * n * n * 4);
  }
  run(sc, x0, y0, x1, y1) {
    const n = this.n, p = this.ptr;
    M._dflw_grid(sc, n, n, x0, y0, x1, y1, p, p + 4 * n * n, p + 8 * n * n);
    const f = M.HEAPF32, o = p >> 2;
    this.u = f.subarray(o, o + n * n);
    this.d = f.subarray(o + n * n, o + 2 * n * n);
    this.g = f.subarray(o + 2 * n * n, o + 3 * n * n);
  }
}

function twoVertices(alpha) {
  M._dflw_two_segments(alpha, buf);
  return getDoubles(buf, 6);
}

function buildPolyline(sc, v, join, p, trim) {
  setDoubles(buf, v);
  if (trim === 'exact') return M._dflw_scene_exact(sc, buf, v.length / 2, JOINS.indexOf(join), p);
  return M._dflw_scene_polyline(sc, buf, v.length / 2, JOINS.indexOf(join), p, TRIMS.indexOf(trim));
}

/* ---- drawing ---------------------------------------------------------------- */

const STOPS = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
function ramp(t, out) {
  if (!Number.isFinite(t)) { out[0] = out[1] = out[2] = 128; return; }
  t = Math.min(1, Math.max(0, t)) * (STOPS.length - 1);
  const i = Math.min(STOPS.length - 2, Math.floor(t)), f = t - i, a = STOPS[i], b = STOPS[i + 1];
  out[0] = a[0] + f * (b[0] - a[0]); out[1] = a[1] + f * (b[1] - a[1]); out[2] = a[2] + f * (b[2] - a[2]);
}
function diverge(t, out) { /* t in [-1, 1]: blue - white - red; grey where there is no field */
  if (!Number.isFinite(t)) { out[0] = out[1] = out[2] = 128; return; }
  t = Math.min(1, Math.max(-1, t));
  if (t < 0) { out[0] = 255 * (1 + t); out[1] = 255 * (1 + t); out[2] = 255; }
  else { out[0] = 255; out[1] = 255 * (1 - t); out[2] = 255 * (1 - t); }
}

/* Isolines where floor(a / step) changes towards the right or lower neighbour. */
function isoMask(a, n, step, mask, bit) {
  for (let j = 0; j < n; j++)
    for (let i = 0; i < n; i++) {
      const k = j * n + i, c = Math.floor(a[k] / step);
      if ((i + 1 < n && Math.floor(a[k + 1] / step) !== c) || (j + 1 < n && Math.floor(a[k + n] / step) !== c))
        mask[k] |= bit;
    }
}

function paintField(ctx, grid, view) {
  const n = grid.n, img = ctx.createImageData(n, n), px = img.data, rgb = [0, 0, 0];
  const mask = new Uint8Array(n * n), step = 0.025;
  isoMask(grid.d, n, step, mask, 1);
  isoMask(grid.u, n, step, mask, 2);
  for (let k = 0; k < n * n; k++) {
    if (view === 'err') diverge((grid.u[k] - grid.d[k]) / 0.05, rgb);
    else ramp(grid.u[k] / 0.6, rgb);
    let r = rgb[0], g = rgb[1], b = rgb[2];
    if (mask[k] & 1) r = g = b = 0;
    if (mask[k] & 2) r = g = b = 255;
    px[4 * k] = r; px[4 * k + 1] = g; px[4 * k + 2] = b; px[4 * k + 3] = 255;
  }
  ctx.putImageData(img, 0, 0);
}

function paintGrad(ctx, grid) {
  const n = grid.n, img = ctx.createImageData(n, n), px = img.data, rgb = [0, 0, 0];
  for (let k = 0; k < n * n; k++) {
    diverge((grid.g[k] - 1) / 0.5, rgb);
    px[4 * k] = rgb[0]; px[4 * k + 1] = rgb[1]; px[4 * k + 2] = rgb[2]; px[4 * k + 3] = 255;
  }
  ctx.putImageData(img, 0, 0);
}

function toPx(x, y, w, h) { return [x * w, (1 - y) * h]; }

function drawPolyline(ctx, v, colour) {
  const w = ctx.canvas.width, h = ctx.canvas.height;
  ctx.strokeStyle = colour; ctx.lineWidth = 2; ctx.beginPath();
  for (let i = 0; i < v.length; i += 2) {
    const [X, Y] = toPx(v[i], v[i + 1], w, h);
    if (i) ctx.lineTo(X, Y); else ctx.moveTo(X, Y);
  }
  ctx.stroke();
}

function fmt(x) { return Number.isFinite(x) ? x.toPrecision(6) : String(x); }

function iniText(lines) { return lines.join('\n') + '\n'; }

function fieldIni(comment, v, join, p, trim) {
  const pts = [];
  for (let i = 0; i < v.length; i += 2) pts.push(v[i] + ' ' + v[i + 1]);
  return iniText([
    '# ' + comment,
    '#   build/dflab probe THIS.ini --points P.csv      (P.csv: header x,y)',
    '[field]', 'kind = rfunc', 'vertices = ' + pts.join('; '), 'closed = false',
    'join = ' + join, 'p = ' + p, 'trim = ' + trim]);
}

/* ---- panel 1: two segments ---------------------------------------------------- */

const two = {};
function drawTwo() {
  const sc = scenes.two;
  const v = twoVertices(state.alpha);
  two.v = v;
  const st = buildPolyline(sc, v, state.join, state.p, state.trim);
  const msg = document.getElementById('two-msg');
  msg.textContent = st ? 'dflab: ' + errorOf(sc) : '';
  two.grid.run(sc, 0, 0, 1, 1);
  paintField(two.cu, two.grid, state.view);
  drawPolyline(two.cu, v, '#f0f');
  paintGrad(two.cg, two.grid);
  drawPolyline(two.cg, v, '#000');
  drawBounds(st === 0);
  const c = 0.05;
  setDoubles(buf, [v[2], v[3], 0, 1]);
  const bulge = M._dflw_bulge(sc, buf, buf + 16, c, 0.35);
  const p = state.p;
  const theory = state.join === 'requiv' ? Math.pow(2, 1 / p) - 1
    : state.join === 'rconj' ? 1 / (2 - Math.pow(2, 1 / p)) - 1 : 0;
  const bel = document.getElementById('two-bulge');
  bel.dataset.bulge = String(bulge);
  bel.textContent =
    'Joint bulge of the level set u = ' + c + ' on the outer bisector: measured ' + fmt(bulge) +
    ', exact-distance theory ' + fmt(theory) +
    (state.join === 'requiv' ? ' (2^(1/p) − 1)' : state.join === 'rconj' ? ' (1/(2 − 2^(1/p)) − 1)' : ' (eq. 20 removes it)') +
    (state.trim === 'exact' ? '.' : '; the trim moves the measured value away from the theory.');
  document.getElementById('two-ini').textContent = state.trim === 'exact'
    ? '# The exact segment distances joined (rfunc/exact_polyline) have no [field] kind:\n' +
      '# dflab probe cannot evaluate this setting; choose a trim for a config.\n'
    : fieldIni('two segments at alpha = ' + state.alpha + ' degrees', v, state.join, state.p, state.trim);
}

function drawBounds(ok) {
  const ctx = two.cb, w = ctx.canvas.width, h = ctx.canvas.height, m = 28, nb = 91;
  ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, w, h);
  const X = phi => m + (w - 2 * m + 10) * phi / (Math.PI / 2), Y = g => h - m - (h - 2 * m) * g / 1.5;
  ctx.strokeStyle = '#999'; ctx.lineWidth = 1; ctx.strokeRect(m, Y(1.5), w - 2 * m + 10, Y(0) - Y(1.5));
  ctx.fillStyle = '#000'; ctx.font = '11px sans-serif';
  ctx.fillText('0', m - 3, h - m + 12); ctx.fillText('π/2', X(Math.PI / 2) - 10, h - m + 12);
  ctx.fillText('φ', (w) / 2, h - 6);
  for (const g of [0, 0.5, 1, 1.5]) ctx.fillText(String(g), 2, Y(g) + 4);
  ctx.setLineDash([3, 3]); ctx.beginPath(); ctx.moveTo(m, Y(1)); ctx.lineTo(X(Math.PI / 2), Y(1)); ctx.stroke(); ctx.setLineDash([]);
  if (!ok) return;
  const lo = buf + 8 * 64, hi = lo + 8 * nb;
  const st = M._dflw_bounds(scenes.two, JOINS.indexOf(state.join), state.p, nb, lo, hi);
  if (st === 0) {
    const L = getDoubles(lo, nb), H = getDoubles(hi, nb);
    for (const [arr, col] of [[L, '#1565c0'], [H, '#c62828']]) {
      ctx.strokeStyle = col; ctx.lineWidth = 2; ctx.beginPath();
      arr.forEach((g, i) => { const x = X(i * (Math.PI / 2) / (nb - 1)); if (i) ctx.lineTo(x, Y(g)); else ctx.moveTo(x, Y(g)); });
      ctx.stroke();
    }
  } else {
    ctx.fillText('eq. 13–14 do not apply to the corrected join', m + 4, Y(1.4));
  }
  const nr = 180, g = buf + 8 * 300, ph = g + 8 * nr;
  setDoubles(buf, [two.v[2], two.v[3]]);
  M._dflw_ring(scenes.two, buf, 0.05, nr, g, ph);
  const G = getDoubles(g, nr), P = getDoubles(ph, nr);
  ctx.fillStyle = '#000';
  for (let i = 0; i < nr; i++) if (Number.isFinite(P[i])) ctx.fillRect(X(P[i]) - 1, Y(G[i]) - 1, 3, 3);
}

/* ---- panel 2: normalization order --------------------------------------------- */

const norm = {};
function normPoint() {
  const i = state.nseg, a = [NORM_V[2 * i], NORM_V[2 * i + 1]], b = [NORM_V[2 * i + 2], NORM_V[2 * i + 3]];
  const t = state.nt, ex = b[0] - a[0], ey = b[1] - a[1], L = Math.hypot(ex, ey);
  const x = [a[0] + t * ex, a[1] + t * ey];
  const nrm = [state.nside * ey / L, -state.nside * ex / L];
  return { x, nrm, L };
}

function normOrderTheory(join, p, trim) {
  if (join === 'rconj' && p === 1) return null;
  const o = join === 'rconj' ? p - 1 : p;
  return trim === 'disk_smooth' ? Math.min(o, 6) : o;
}

function drawNorm() {
  const sc = scenes.norm;
  const st = buildPolyline(sc, NORM_V, state.njoin, state.np, state.ntrim);
  const msg = document.getElementById('norm-msg');
  msg.textContent = st ? 'dflab: ' + errorOf(sc) : '';
  norm.grid.run(sc, 0, 0, 1, 1);
  paintField(norm.cu, norm.grid, 'u');
  drawPolyline(norm.cu, NORM_V, '#f0f');
  const { x, nrm, L } = normPoint();
  const ctx = norm.cu, w = ctx.canvas.width, h = ctx.canvas.height;
  const [X, Y] = toPx(x[0], x[1], w, h), [X2, Y2] = toPx(x[0] + 0.12 * nrm[0], x[1] + 0.12 * nrm[1], w, h);
  ctx.strokeStyle = '#f00'; ctx.lineWidth = 2; ctx.beginPath(); ctx.moveTo(X, Y); ctx.lineTo(X2, Y2); ctx.stroke();
  ctx.fillStyle = '#f00'; ctx.beginPath(); ctx.arc(X, Y, 4, 0, 2 * Math.PI); ctx.fill();
  const body = document.querySelector('#norm-table tbody');
  body.textContent = '';
  const out = document.getElementById('norm-order');
  const theory = normOrderTheory(state.njoin, state.np, state.ntrim);
  if (st) { out.textContent = 'no field: ' + errorOf(sc); out.dataset.order = 'n/a'; out.dataset.theory = 'n/a'; norm.d = null; return; }
  setDoubles(buf, [x[0], x[1], nrm[0], nrm[1]]);
  const K = 12, dptr = buf + 8 * 8;
  let d = null;
  if (M._dflw_jet(sc, buf, buf + 16, K + 1, dptr) === 0) d = getDoubles(dptr, K + 1);
  norm.d = d;
  let fact = 1;
  for (let k = 1; k <= K; k++) {
    fact *= k;
    const tr = document.createElement('tr');
    const dk = d ? d[k - 1] : NaN, a = Math.abs(dk / fact) * Math.pow(L, k - 1);
    for (const s of [String(k), fmt(dk), a.toExponential(2)]) { const td = document.createElement('td'); td.textContent = s; tr.appendChild(td); }
    if (k > 1 && a > 1e-9) tr.className = 'nonzero';
    body.appendChild(tr);
  }
  const kptr = buf + 8 * 40;
  const order = M._dflw_order(sc, buf, buf + 16, 16, L, 1e-9, kptr);
  const why = state.ntrim === 'disk_smooth' && theory === 6 && (state.njoin === 'rconj' ? state.np - 1 : state.np) > 6
    ? 'the smooth trim (eq. 5) caps it at 6'
    : state.njoin === 'rconj' ? 'R-conjunction gives p − 1 (eq. 7)'
    : state.njoin === 'requiv' ? 'R-equivalence gives p (eq. 6)' : 'the corrected join keeps eq. 6\'s order p';
  out.dataset.order = String(order);
  out.dataset.theory = String(theory);
  out.textContent = 'Measured order ' + order + ' (eq. 1 with tolerance 1e-9 on the scale L = ' + fmt(L) +
    '); bs04: ' + theory + ', because ' + why + '.';
  document.getElementById('norm-ini').textContent = fieldIni(
    'the bs04_normalization polyline; probe the point with --jet 13 and a column dx,dy = ' + nrm[0] + ',' + nrm[1],
    NORM_V, state.njoin, state.np, state.ntrim);
}

function normClick(ev) {
  const r = norm.cu.canvas.getBoundingClientRect();
  const px = (ev.clientX - r.left) / r.width, py = 1 - (ev.clientY - r.top) / r.height;
  let best = null;
  for (let i = 0; i < 4; i++) {
    const ax = NORM_V[2 * i], ay = NORM_V[2 * i + 1], ex = NORM_V[2 * i + 2] - ax, ey = NORM_V[2 * i + 3] - ay;
    const t = Math.min(0.95, Math.max(0.05, ((px - ax) * ex + (py - ay) * ey) / (ex * ex + ey * ey)));
    const dx = px - (ax + t * ex), dy = py - (ay + t * ey), dd = dx * dx + dy * dy;
    if (!best || dd < best.dd) best = { i, t, dd, side: (dx * ey - dy * ex) >= 0 ? 1 : -1 };
  }
  state.nseg = best.i; state.nt = Math.round(best.t * 100) / 100; state.nside = best.side;
  syncControls(); update(['norm']);
}

/* ---- panel 3: bulging of a curve ------------------------------------------------ */

const bul = {};
function bulgeCp() { return state.cp ? state.cp.split(',').map(Number) : SHAPES[state.shape].slice(); }
function drawBulge() {
  const sc = scenes.bulge, cp = bulgeCp(), eps = Number(state.eps);
  setDoubles(buf, cp);
  const st = M._dflw_scene_curve(sc, buf, cp.length / 2, 4, eps, 0, state.bp, TRIMS.indexOf('strip'));
  document.getElementById('bulge-msg').textContent = st ? 'dflab: ' + errorOf(sc) : '';
  bul.grid.run(sc, -0.1, -0.1, 1.1, 1.1);
  paintField(bul.cu, bul.grid, 'u');
  const ctx = bul.cu, w = ctx.canvas.width, h = ctx.canvas.height;
  const P = (x, y) => [(x + 0.1) / 1.2 * w, (1.1 - y) / 1.2 * h];
  const nv = M._dflw_scene_nvertices(sc);
  const v = nv ? getDoubles(M._dflw_scene_vertices(sc), 2 * nv) : [];
  ctx.strokeStyle = '#f0f'; ctx.lineWidth = 1.5; ctx.beginPath();
  for (let i = 0; i < v.length; i += 2) { const [X, Y] = P(v[i], v[i + 1]); if (i) ctx.lineTo(X, Y); else ctx.moveTo(X, Y); }
  ctx.stroke();
  ctx.strokeStyle = '#bbb'; ctx.setLineDash([4, 3]); ctx.beginPath();
  for (let i = 0; i < cp.length; i += 2) { const [X, Y] = P(cp[i], cp[i + 1]); if (i) ctx.lineTo(X, Y); else ctx.moveTo(X, Y); }
  ctx.stroke(); ctx.setLineDash([]);
  ctx.fillStyle = '#ddd';
  for (let i = 0; i < cp.length; i += 2) { const [X, Y] = P(cp[i], cp[i + 1]); ctx.fillRect(X - 4, Y - 4, 8, 8); }
  bul.P = P;
  /* The bs04_bulging study's measure (field/curveprobe through dflw_curve_bulge):
   * r = (s - delta) / delta along rays normal to the exact curve. */
  const c = 0.05, rp = buf + 8 * 700;
  const rst = nv ? M._dflw_curve_bulge(sc, c, 801, 64, rp)  /* rays, cap_rays of bs04_bulging.ini */ : 1;
  const r = getDoubles(rp, 4);
  const mel = document.getElementById('bulge-m');
  mel.dataset.bulge = String(r[0]);
  mel.dataset.joint = String(r[1]);
  mel.textContent = !nv ? '' : rst ? 'bulge measure: ' + errorOf(sc)
    : 'Polyline of ' + (nv - 1) + ' segments within ε = ' + eps + '. Bulge of the level set u = δ = ' + c +
      ' (bs04_bulging\'s measure: rays along the exact curve\'s normals, r = (s − δ)/δ): max r = ' + fmt(r[0]) +
      '; at the joints ' + fmt(r[1]) + ', on the sides ' + fmt(r[2]) + ', around the free ends ' + fmt(r[3]) +
      '. A joint of collinear parts gives 2^(1/p) − 1 = ' + fmt(Math.pow(2, 1 / state.bp) - 1) + '.';
  const pts = [];
  for (let i = 0; i < cp.length; i += 2) pts.push(cp[i] + ' ' + cp[i + 1]);
  document.getElementById('bulge-ini').textContent = iniText([
    '# the ' + state.shape + ' curve, polygonized within eps, strip trims, joined by R-equivalence',
    '#   build/dflab probe THIS.ini --points P.csv      (P.csv: header x,y)',
    '[field]', 'kind = rfunc', 'curve = shape', 'eps = ' + eps, 'join = requiv', 'p = ' + state.bp, 'trim = strip', '',
    '[shape]', 'kind = bspline_curve', 'order = 4', 'control = ' + pts.join('; ')]);
}

function bulgeDrag() {
  const cv = bul.cu.canvas;
  let drag = -1;
  const at = ev => {
    const r = cv.getBoundingClientRect();
    return [(ev.clientX - r.left) / r.width * 1.2 - 0.1, 1.1 - (ev.clientY - r.top) / r.height * 1.2];
  };
  cv.addEventListener('pointerdown', ev => {
    const [x, y] = at(ev), cp = bulgeCp();
    let best = -1, bd = 0.03 * 0.03;
    for (let i = 0; i < cp.length; i += 2) {
      const dd = (cp[i] - x) ** 2 + (cp[i + 1] - y) ** 2;
      if (dd < bd) { bd = dd; best = i; }
    }
    drag = best;
    if (drag >= 0) cv.setPointerCapture(ev.pointerId);
  });
  cv.addEventListener('pointermove', ev => {
    if (drag < 0) return;
    const [x, y] = at(ev), cp = bulgeCp();
    cp[drag] = Math.round(x * 1000) / 1000; cp[drag + 1] = Math.round(y * 1000) / 1000;
    state.cp = cp.join(',');
    update(['bulge']);
  });
  cv.addEventListener('pointerup', () => { drag = -1; });
}

/* ---- controls and URL -------------------------------------------------------------- */

const BIND = [
  ['two-alpha', 'alpha', Number], ['two-p', 'p', Number], ['two-join', 'join', String],
  ['two-trim', 'trim', String], ['two-view', 'view', String],
  ['norm-p', 'np', Number], ['norm-join', 'njoin', String], ['norm-trim', 'ntrim', String],
  ['norm-seg', 'nseg', Number], ['norm-t', 'nt', Number],
  ['bulge-shape', 'shape', String], ['bulge-eps', 'eps', String], ['bulge-p', 'bp', Number],
];

function syncControls() {
  for (const [id, key] of BIND) {
    const el = document.getElementById(id);
    el.value = String(state[key]);
    const o = document.getElementById(id + '-v');
    if (o) o.textContent = String(state[key]);
  }
}

/* Redraws the panels named (all by default): a control redraws its own
 * panel only, so that dragging on the curve does not recompute the others. */
function update(panels) {
  const all = !panels;
  if (all || panels.includes('two')) drawTwo();
  if (all || panels.includes('norm')) drawNorm();
  if (all || panels.includes('bulge')) drawBulge();
  const h = formatHash(state);
  if (h !== location.hash && !(h === '' && location.hash === ''))
    history.replaceState(null, '', h || location.pathname + location.search);
}

function toggle(btn, pre) {
  const show = pre.hidden;
  pre.hidden = !show;
  btn.setAttribute('aria-expanded', String(show));
}

/* Hooks for the browser test and the benchmark: the same library calls the
 * panels make. */
function exposeHooks() {
  window.dflab = {
    state: () => Object.assign({}, state),
    ini: panel => document.getElementById(panel + '-ini').textContent,
    /* u, gx, gy of the two-segment field at points [[x, y], ...]. */
    probe(points) {
      const m = points.length, p = M._malloc(16 * m), v = M._malloc(8 * m), g = M._malloc(16 * m);
      setDoubles(p, points.flat());
      M._dflw_eval(scenes.two, m, p, v, g);
      const V = getDoubles(v, m), G = getDoubles(g, 2 * m);
      M._free(p); M._free(v); M._free(g);
      return points.map((_, i) => [V[i], G[2 * i], G[2 * i + 1]]);
    },
    normal: () => Object.assign(normPoint(), { d: norm.d }),
    /* Frames per second of the two-segment panel (field at 256^2 and both maps). */
    bench(frames) {
      const t0 = performance.now();
      for (let i = 0; i < frames; i++) { state.alpha = 60 + (i % 240); drawTwo(); }
      return frames / ((performance.now() - t0) / 1000);
    },
  };
}

createDflab().then(mod => {
  M = mod;
  buf = M._malloc(8 * BUF_DOUBLES);
  for (const k of ['two', 'norm', 'bulge']) scenes[k] = M._dflw_scene_new();
  two.grid = new Grid(N); norm.grid = new Grid(N); bul.grid = new Grid(320);
  two.cu = document.getElementById('two-u').getContext('2d');
  two.cg = document.getElementById('two-g').getContext('2d');
  two.cb = document.getElementById('two-b').getContext('2d');
  norm.cu = document.getElementById('norm-u').getContext('2d');
  bul.cu = document.getElementById('bulge-u').getContext('2d');
  for (const el of document.querySelectorAll('select[data-options="joins"]'))
    JOINS.forEach((j, i) => el.add(new Option(JOIN_LABELS[i], j)));
  Object.assign(state, parseHash(location.hash));
  syncControls();
  for (const [id, key, conv] of BIND) {
    document.getElementById(id).addEventListener('input', ev => {
      state[key] = conv(ev.target.value);
      if (key === 'shape') state.cp = '';
      syncControls(); update([id.split('-')[0]]);
    });
  }
  window.addEventListener('hashchange', () => { Object.assign(state, parseHash(location.hash)); syncControls(); update(); });
  for (const k of ['two', 'norm', 'bulge'])
    document.getElementById(k + '-config').addEventListener('click', ev => toggle(ev.target, document.getElementById(k + '-ini')));
  document.getElementById('norm-u').addEventListener('click', normClick);
  document.getElementById('bulge-reset').addEventListener('click', () => { state.cp = ''; update(['bulge']); });
  bulgeDrag();
  exposeHooks();
  update();
  const st = document.getElementById('status');
  st.textContent = 'dflab library loaded (WebAssembly).';
  st.dataset.ready = '1';
});

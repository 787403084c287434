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
  alpha: 120, p: 2, p2: 8, delta: 0.05, join: 'requiv', trim: 'disk', view: 'u',
  np: 4, njoin: 'requiv', ntrim: 'disk', nseg: 1, nt: 0.5, nside: 1,
  shape: 'W', eps: '0.02', bp: 2, cp: '',
};
const state = Object.assign({}, DEFAULTS);
const EPS_LIST = ['0.05', '0.02', '0.01', '0.005', '0.002', '0.001'];
/* What each URL key accepts: numbers (integer or not, range, decimals kept)
 * or a list of names. */
const SPEC = {
  alpha: { int: true, min: 10, max: 350 }, p: { int: true, min: 1, max: 12 }, p2: { int: true, min: 1, max: 12 },
  delta: { min: 0.01, max: 0.2, dec: 2 }, np: { int: true, min: 1, max: 12 }, bp: { int: true, min: 1, max: 12 },
  nseg: { int: true, min: 0, max: 3 }, nt: { min: 0.05, max: 0.95, dec: 2 }, nside: { one: [1, -1] },
  join: { names: JOINS }, njoin: { names: JOINS }, trim: { names: ['exact'].concat(TRIMS) },
  ntrim: { names: ['disk', 'disk_smooth', 'strip'] }, view: { names: ['u', 'err'] },
  shape: { names: Object.keys(SHAPES) }, eps: { names: EPS_LIST },
};
const NUMBER_RE = /^[-+]?(\d+\.?\d*|\.\d+)(e[-+]?\d+)?$/i;

/* The state of an address and the problems met (each "key=value: what was
 * done"): an invalid value is replaced (clamped, rounded or the default)
 * and said so on the page, never silently. */
function parseHash(h) {
  const s = Object.assign({}, DEFAULTS), problems = [];
  for (const kv of h.replace(/^#/, '').split('&')) {
    if (!kv) continue;
    const i = kv.indexOf('=');
    let k, v;
    try {
      k = decodeURIComponent(i < 0 ? kv : kv.slice(0, i));
      v = decodeURIComponent(i < 0 ? '' : kv.slice(i + 1));
    } catch (e) { problems.push(`"${kv}": not a valid escape, ignored`); continue; }
    const said = k + '=' + v;
    if (!(k in DEFAULTS)) { problems.push(`${said}: unknown key "${k}", ignored`); continue; }
    const sp = SPEC[k];
    if (k === 'cp') {
      if (!v || v.split(',').every(x => NUMBER_RE.test(x.trim()))) s.cp = v;
      else problems.push(`cp=${v}: not a list of numbers; using the curve's own control points`);
      continue;
    }
    if (sp.names) {
      if (sp.names.includes(v)) s[k] = v;
      else problems.push(`${said}: expected one of ${sp.names.join(', ')}; using ${DEFAULTS[k]}`);
      continue;
    }
    if (!NUMBER_RE.test(v.trim())) { problems.push(`${said}: not a number; using ${DEFAULTS[k]}`); continue; }
    let x = Number(v);
    if (sp.one) {
      if (sp.one.includes(x)) s[k] = x;
      else problems.push(`${said}: expected ${sp.one.join(' or ')}; using ${DEFAULTS[k]}`);
      continue;
    }
    const why = [];
    if (sp.int && x !== Math.round(x)) { x = Math.round(x); why.push('not an integer'); }
    if (sp.dec && Math.abs(x - Number(x.toFixed(sp.dec))) > 1e-12) { x = Number(x.toFixed(sp.dec)); why.push(`more than ${sp.dec} decimals`); }
    if (x < sp.min || x > sp.max) { x = Math.min(sp.max, Math.max(sp.min, x)); why.push(`outside ${sp.min}…${sp.max}`); }
    s[k] = x;
    if (why.length) problems.push(`${said}: ${why.join(', ')}; using ${x}`);
  }
  /* a cp list must fit the shape finally chosen */
  if (s.cp) {
    const c = s.cp.split(',').map(Number);
    if (c.length !== SHAPES[s.shape].length) { problems.push(`cp: ${c.length / 2} control points do not fit the ${s.shape} curve, using its own`); s.cp = ''; }
  }
  return { state: s, problems };
}

/* Shows what parseHash could not use, where the page begins. */
function applyHash() {
  const r = parseHash(location.hash);
  Object.assign(state, r.state);
  const el = document.getElementById('url-msg');
  el.textContent = r.problems.length
    ? 'The address has invalid values, replaced: ' + r.problems.join('; ') + '.' : '';
  el.dataset.problems = String(r.problems.length);
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

/* Pixels where a crosses the level c within their 3 x 3 neighbourhood: a
 * curve two to three pixels wide. */
function levelMask(a, n, c, mask, bit) {
  for (let j = 0; j < n; j++)
    for (let i = 0; i < n; i++) {
      const k = j * n + i, s = a[k] < c;
      for (let dj = -1; dj <= 1; dj++)
        for (let di = -1; di <= 1; di++) {
          const jj = j + dj, ii = i + di;
          if (jj < 0 || jj >= n || ii < 0 || ii >= n || (di | dj) === 0) continue;
          if ((a[jj * n + ii] < c) !== s) { mask[k] |= bit; dj = di = 2; }
        }
    }
}

/* The field's colour map: u on the ramp over [0, U_MAX], or u − d over
 * [−ERR_MAX, ERR_MAX]; the colour bar draws the same functions. */
const U_MAX = 0.6, ERR_MAX = 0.05, SHADE = [255, 128, 0], SHADE_A = 0.75;
function colourOf(view, v, out) {
  if (view === 'err') diverge(v / ERR_MAX, out); else ramp(v / U_MAX, out);
}

/* u in colour; the level set u = delta (white) and the exact offset d =
 * delta (black) drawn thick, the band between them (the bulge: u < delta
 * <= d, or the reverse) shaded orange.  Returns the band's pixel count. */
function paintField(ctx, grid, view, delta) {
  const n = grid.n, img = ctx.createImageData(n, n), px = img.data, rgb = [0, 0, 0];
  const mask = new Uint8Array(n * n);
  levelMask(grid.d, n, delta, mask, 1);
  levelMask(grid.u, n, delta, mask, 2);
  let band = 0;
  for (let k = 0; k < n * n; k++) {
    colourOf(view, view === 'err' ? grid.u[k] - grid.d[k] : grid.u[k], rgb);
    let r = rgb[0], g = rgb[1], b = rgb[2];
    if ((grid.u[k] < delta) !== (grid.d[k] < delta) && Number.isFinite(grid.u[k])) {
      band++;
      r += SHADE_A * (SHADE[0] - r); g += SHADE_A * (SHADE[1] - g); b += SHADE_A * (SHADE[2] - b);
    }
    if (mask[k] & 1) r = g = b = 0;
    if (mask[k] & 2) r = g = b = 255;
    px[4 * k] = r; px[4 * k + 1] = g; px[4 * k + 2] = b; px[4 * k + 3] = 255;
  }
  ctx.putImageData(img, 0, 0);
  ctx.canvas.dataset.band = String(band);
  return band;
}

/* The colour bar of the field maps: the ramp from bottom (min) to top
 * (max) with its numbers, and the level delta marked. */
const BAR = { x: 12, w: 16, top: 8, bottom: 248 };
function drawBar(ctx, view, delta) {
  const w = ctx.canvas.width, h = ctx.canvas.height, rgb = [0, 0, 0];
  const lo = view === 'err' ? -ERR_MAX : 0, hi = view === 'err' ? ERR_MAX : U_MAX;
  const ticks = view === 'err' ? [-0.05, -0.025, 0, 0.025, 0.05] : [0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6];
  const Y = v => BAR.bottom - (v - lo) / (hi - lo) * (BAR.bottom - BAR.top);
  ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, w, h);
  for (let y = BAR.top; y <= BAR.bottom; y++) {
    colourOf(view, lo + (BAR.bottom - y) / (BAR.bottom - BAR.top) * (hi - lo), rgb);
    ctx.fillStyle = `rgb(${rgb[0]},${rgb[1]},${rgb[2]})`;
    ctx.fillRect(BAR.x, y, BAR.w, 1);
  }
  ctx.strokeStyle = '#000'; ctx.lineWidth = 1; ctx.fillStyle = '#000'; ctx.font = '10px sans-serif';
  ctx.strokeRect(BAR.x - 0.5, BAR.top - 0.5, BAR.w + 1, BAR.bottom - BAR.top + 1);
  for (const t of ticks) {
    const y = Math.round(Y(t)) + 0.5;
    ctx.beginPath(); ctx.moveTo(BAR.x + BAR.w, y); ctx.lineTo(BAR.x + BAR.w + 4, y); ctx.stroke();
    ctx.fillText((t === hi && view !== 'err' ? '≥ ' : '') + String(t), BAR.x + BAR.w + 6, y + 3);
  }
  if (view !== 'err') { /* the level delta */
    const y = Math.round(Y(delta)) + 0.5;
    ctx.strokeStyle = '#fff'; ctx.lineWidth = 2; ctx.beginPath(); ctx.moveTo(BAR.x, y); ctx.lineTo(BAR.x + BAR.w, y); ctx.stroke();
    ctx.fillStyle = '#000'; ctx.fillText('δ', 1, y + 3);
  }
  const c = ctx.canvas;
  Object.assign(c.dataset, { min: String(lo), max: String(hi), x: String(BAR.x + BAR.w / 2),
    top: String(BAR.top), bottom: String(BAR.bottom), ticks: ticks.join(',') });
  c.setAttribute('aria-label', (view === 'err' ? 'colour bar of u − d from ' : 'colour bar of u from ') + lo + ' to ' + hi +
    ', ticks ' + ticks.join(', '));
  document.getElementById('two-bar-cap').textContent = view === 'err' ? 'colour of u − d' : 'colour of u (all maps)';
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

function fmtSmall(x) { return Math.abs(x) < 1e-12 ? '0 (|·| < 1e-12)' : fmt(x); }
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
function bulgeTheory(join, p) {
  return join === 'requiv' ? Math.pow(2, 1 / p) - 1 : join === 'rconj' ? 1 / (2 - Math.pow(2, 1 / p)) - 1 : 0;
}

/* The joint bulge of u = c on the outer bisector: the ray from the vertex
 * into the reflex side (dflw_two_bisector: downwards for alpha > 180),
 * where d = |x - v| and t/c - 1 is the bulge. */
function jointBulge(sc, v, c) {
  M._dflw_two_bisector(state.alpha, buf + 16);
  setDoubles(buf, [v[2], v[3]]);
  return M._dflw_bulge(sc, buf, buf + 16, c, 0.35);
}

/* For alpha > 180: what the upward ray (the convex side) measures, from the
 * library: t/c - 1 where u = c, and d/c - 1 there. */
function convexNote(sc, v, c) {
  setDoubles(buf, [v[2], v[3], 0, 1]);
  const tb = M._dflw_bulge(sc, buf, buf + 16, c, 0.35), t = c * (1 + tb);
  setDoubles(buf, [v[2], v[3] + t]);
  M._dflw_dist(sc, 1, buf, buf + 16);
  const d = getDoubles(buf + 16, 1)[0];
  const bel = document.getElementById('two-bulge');
  bel.dataset.convexT = String(tb); bel.dataset.convexD = String(d / c - 1);
  return ' Upwards, on the convex side, the nearest points lie on the arms, not at the joint (d = t sin(' +
    (180 - state.alpha / 2) + '°) at distance t from it), so t/δ − 1 = ' + fmt(tb) + ' there is no bulge and no ' +
    'finite-radius effect (it is the same for every δ); against d the level set u = δ lies ' + fmt(d / c - 1) +
    ' δ outside d = δ there, since eq. 20 subtracts |x − v|^−p, which cancels the extra h^−p only in the hatched sector.';
}

function drawTwo() {
  const sc = scenes.two;
  const v = twoVertices(state.alpha);
  two.v = v;
  const st = buildPolyline(sc, v, state.join, state.p, state.trim);
  const msg = document.getElementById('two-msg');
  msg.textContent = st ? 'dflab: ' + errorOf(sc) : '';
  two.grid.run(sc, 0, 0, 1, 1);
  two.band = paintField(two.cu, two.grid, state.view, state.delta);
  drawPolyline(two.cu, v, '#f0f');
  paintGrad(two.cg, two.grid);
  drawPolyline(two.cg, v, '#000');
  drawBounds(st === 0);
  /* the same at the comparison order p2 */
  const sc2 = scenes.two2, st2 = buildPolyline(sc2, v, state.join, state.p2, state.trim);
  if (st2 && !st) msg.textContent = 'dflab (p₂ = ' + state.p2 + '): ' + errorOf(sc2);
  two.grid2.run(sc2, 0, 0, 1, 1);
  two.band2 = paintField(two.cu2, two.grid2, state.view, state.delta);
  drawPolyline(two.cu2, v, '#f0f');
  document.getElementById('two-u-cap').textContent =
    'p = ' + state.p + ': u (colour), u = δ (white), d = δ (black), δ = ' + state.delta + '; orange: the band between them';
  document.getElementById('two-u2-cap').textContent = 'p₂ = ' + state.p2 + ': the same field at the comparison order';
  drawBar(two.cbar, state.view, state.delta);
  const c = 0.05;
  const bulge = jointBulge(sc, v, c), bulge2 = jointBulge(sc2, v, c);
  const bel = document.getElementById('two-bulge');
  bel.dataset.bulge = String(bulge);
  bel.dataset.bulge2 = String(bulge2);
  const formula = state.join === 'requiv' ? ' (2^(1/p) − 1)' : state.join === 'rconj' ? ' (1/(2 − 2^(1/p)) − 1)'
    : ' (eq. 20 removes it in the hatched sector)';
  const down = state.alpha > 180;
  bel.textContent =
    'Joint bulge of the level set u = ' + c + ' on the outer bisector (the ray from the joint into the reflex side, ' +
    (down ? 'downwards since α > 180°' : 'upwards') + ', where d = |x − v|): measured ' + fmtSmall(bulge) + ' at p = ' + state.p +
    ', ' + fmtSmall(bulge2) + ' at p₂ = ' + state.p2 + '; exact-distance theory ' + fmt(bulgeTheory(state.join, state.p)) +
    ' and ' + fmt(bulgeTheory(state.join, state.p2)) + formula +
    (state.trim === 'exact' ? '.' : '; the trim moves the measured value away from the theory.') +
    (down && state.join === 'requiv_corrected' && state.trim === 'exact' ? convexNote(sc, v, c) : '');
  document.getElementById('two-ini').textContent = state.trim === 'exact'
    ? '# The exact segment distances joined (rfunc/exact_polyline) have no [field] kind:\n' +
      '# dflab probe cannot evaluate this setting; choose a trim for a config.\n'
    : fieldIni('two segments at alpha = ' + state.alpha + ' degrees', v, state.join, state.p, state.trim);
}

/* The bound plot's curves, drawn and listed in its legend with one colour each. */
const BOUND_KEYS = [
  { key: 'hi', colour: '#c62828', kind: 'line', text: 'F₁ + F₂: upper bound of |∇u| (eq. 14)' },
  { key: 'lo', colour: '#1565c0', kind: 'line', text: '|F₁ − F₂|: lower bound (eq. 13)' },
  { key: 'ring', colour: '#000000', kind: 'dot', text: 'measured |∇u| on the circle r = 0.05 around the joint' },
  { key: 'one', colour: '#999999', kind: 'dash', text: '|∇u| = 1 (the exact distance)' },
];
function boundColour(key) { return BOUND_KEYS.find(e => e.key === key).colour; }
function fillLegend() {
  const ul = document.getElementById('two-b-legend');
  for (const e of BOUND_KEYS) {
    const li = document.createElement('li'), sw = document.createElement('span');
    sw.className = 'sw' + (e.kind === 'line' ? '' : ' ' + e.kind);
    if (e.kind === 'dot') sw.style.background = e.colour; else sw.style.borderTopColor = e.colour;
    li.dataset.key = e.key; li.dataset.colour = e.colour;
    li.append(sw, e.text);
    ul.appendChild(li);
  }
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
  ctx.strokeStyle = boundColour('one');
  const y1 = Math.round(Y(1)) + 0.5;   /* on a pixel row: the legend's grey is drawn as such */
  ctx.setLineDash([3, 3]); ctx.beginPath(); ctx.moveTo(m, y1); ctx.lineTo(X(Math.PI / 2), y1); ctx.stroke(); ctx.setLineDash([]);
  if (!ok) return;
  const lo = buf + 8 * 64, hi = lo + 8 * nb;
  const st = M._dflw_bounds(scenes.two, JOINS.indexOf(state.join), state.p, nb, lo, hi);
  if (st === 0) {
    const L = getDoubles(lo, nb), H = getDoubles(hi, nb);
    for (const [arr, col] of [[L, boundColour('lo')], [H, boundColour('hi')]]) {
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
  ctx.fillStyle = boundColour('ring');
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
  paintField(norm.cu, norm.grid, 'u', 0.05);
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
  if (st) {
    out.textContent = 'no field: ' + errorOf(sc); out.dataset.order = 'n/a'; out.dataset.theory = 'n/a'; norm.d = null;
    drawLine(sc, x, nrm, -2);
    return;
  }
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
  drawLine(sc, x, nrm, order);
  out.dataset.order = String(order);
  out.dataset.theory = String(theory);
  out.textContent = 'Measured order ' + order + ' (eq. 1 with tolerance 1e-9 on the scale L = ' + fmt(L) +
    '); bs04: ' + theory + ', because ' + why + '.';
  document.getElementById('norm-ini').textContent = fieldIni(
    'the bs04_normalization polyline; probe the point with --jet 13 and a column dx,dy = ' + nrm[0] + ',' + nrm[1],
    NORM_V, state.njoin, state.np, state.ntrim);
}

/* u(s) and d(s) at x + s nrm (dflw_eval, dflw_dist): linear on [-S, S],
 * and the gap |u - d| on log axes for s in [1e-3, 10^-0.5], where it
 * falls like s^(m+1) for a field normalized to order m. */
const LINE = { S: 0.15, nlin: 301, nlog: 101, e0: -3, e1: -0.5, y0: -17, y1: -1 };
function sampleLine(sc, x, nrm, ss) {
  const m = ss.length, pts = norm.lineBuf, val = pts + 16 * m, dist = val + 8 * m;
  const xy = [];
  for (const s of ss) xy.push(x[0] + s * nrm[0], x[1] + s * nrm[1]);
  setDoubles(pts, xy);
  M._dflw_eval(sc, m, pts, val, 0);
  M._dflw_dist(sc, m, pts, dist);
  return { u: getDoubles(val, m), d: getDoubles(dist, m) };
}

function drawLine(sc, x, nrm, order) {
  const lin = [], lg = [];
  for (let i = 0; i < LINE.nlin; i++) lin.push(-LINE.S + 2 * LINE.S * i / (LINE.nlin - 1));
  for (let i = 0; i < LINE.nlog; i++) lg.push(Math.pow(10, LINE.e0 + (LINE.e1 - LINE.e0) * i / (LINE.nlog - 1)));
  const A = sampleLine(sc, x, nrm, lin), B = sampleLine(sc, x, nrm, lg);
  norm.line = { s: lg, u: B.u, d: B.d, order };
  const red = '#c62828';
  { /* linear */
    const ctx = norm.cs, w = ctx.canvas.width, h = ctx.canvas.height, m = 30;
    const X = s => m + (w - m - 8) * (s + LINE.S) / (2 * LINE.S), Y = v => h - m - (h - m - 8) * v / LINE.S;
    ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, w, h);
    ctx.strokeStyle = '#999'; ctx.lineWidth = 1; ctx.strokeRect(m, 8, w - m - 8, h - m - 8);
    ctx.beginPath(); ctx.moveTo(X(0), 8); ctx.lineTo(X(0), h - m); ctx.stroke();
    ctx.fillStyle = '#000'; ctx.font = '11px sans-serif';
    for (const s of [-LINE.S, 0, LINE.S]) ctx.fillText(String(s), X(s) - (s > 0 ? 22 : s < 0 ? 0 : 3), h - m + 13);
    for (const v of [0, 0.05, 0.1, 0.15]) ctx.fillText(String(v), 2, Y(v) + 4);
    ctx.fillText('s', (w + m) / 2 + 20, h - 4);
    const curve = (arr, col, dash, lw) => {
      ctx.strokeStyle = col; ctx.lineWidth = lw; ctx.setLineDash(dash); ctx.beginPath();
      let on = false;
      arr.forEach((v, i) => {
        if (!Number.isFinite(v)) { on = false; return; }
        const X0 = X(lin[i]), Y0 = Y(Math.min(v, 1.05 * LINE.S));
        if (on) ctx.lineTo(X0, Y0); else ctx.moveTo(X0, Y0);
        on = true;
      });
      ctx.stroke(); ctx.setLineDash([]);
    };
    curve(A.u, red, [], 2.5);
    curve(A.d, '#000', [5, 4], 1.5);
    ctx.fillStyle = red; ctx.fillText('u(s)', m + 6, 22);
    ctx.fillStyle = '#000'; ctx.fillText('d(s)', m + 40, 22);
  }
  { /* log-log gap */
    const ctx = norm.cl, w = ctx.canvas.width, h = ctx.canvas.height, m = 34;
    const X = e => m + (w - m - 8) * (e - LINE.e0) / (LINE.e1 - LINE.e0);
    const Y = e => 8 + (h - m - 8) * (LINE.y1 - e) / (LINE.y1 - LINE.y0);
    ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, w, h);
    ctx.strokeStyle = '#999'; ctx.lineWidth = 1; ctx.strokeRect(m, 8, w - m - 8, h - m - 8);
    ctx.fillStyle = '#000'; ctx.font = '11px sans-serif';
    for (const e of [-3, -2, -1]) ctx.fillText('1e' + e, X(e) - 10, h - m + 13);
    for (const e of [-16, -12, -8, -4]) ctx.fillText('1e' + e, 0, Y(e) + 4);
    ctx.fillText('s', (w + m) / 2, h - 4);
    ctx.save(); ctx.beginPath(); ctx.rect(m, 8, w - m - 8, h - m - 8); ctx.clip();
    ctx.fillStyle = red;
    let ref = null;
    B.u.forEach((u, i) => {
      const g = Math.abs(u - B.d[i]);
      if (!(g > 0) || !Number.isFinite(g)) return;
      const e = Math.log10(lg[i]);
      ctx.fillRect(X(e) - 1.5, Y(Math.log10(g)) - 1.5, 3, 3);
      if (e <= -1.3) ref = [e, Math.log10(g)];   /* anchor: the last point at s <= 0.05 */
    });
    if (ref && order >= 1 && order <= 14) {
      const k = order + 1;
      ctx.strokeStyle = '#000'; ctx.lineWidth = 1; ctx.setLineDash([5, 4]); ctx.beginPath();
      ctx.moveTo(X(LINE.e0), Y(ref[1] + k * (LINE.e0 - ref[0]))); ctx.lineTo(X(LINE.e1), Y(ref[1] + k * (LINE.e1 - ref[0])));
      ctx.stroke(); ctx.setLineDash([]);
    }
    ctx.restore();
    ctx.fillStyle = '#000';
    ctx.fillText(order >= 1 && order <= 14 ? '|u − d| ∝ s^' + (order + 1) + ' (dashed: slope m + 1 = ' + (order + 1) + ')'
      : '|u − d| (red)', m + 4, 22);
  }
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
  paintField(bul.cu, bul.grid, 'u', 0.05);
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
  ['two-trim', 'trim', String], ['two-view', 'view', String], ['two-delta', 'delta', Number], ['two-p2', 'p2', Number],
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
    /* u(s), d(s) at the log-spaced s of the gap plot, and the order shown. */
    line: () => norm.line,
    /* the orange band's pixel counts of the two field maps (p and p2) */
    band: () => [two.band, two.band2],
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
  for (const k of ['two', 'two2', 'norm', 'bulge']) scenes[k] = M._dflw_scene_new();
  two.grid = new Grid(N); two.grid2 = new Grid(N); norm.grid = new Grid(N); bul.grid = new Grid(320);
  two.cu = document.getElementById('two-u').getContext('2d');
  two.cg = document.getElementById('two-g').getContext('2d');
  two.cu2 = document.getElementById('two-u2').getContext('2d');
  two.cbar = document.getElementById('two-bar').getContext('2d');
  fillLegend();
  two.cb = document.getElementById('two-b').getContext('2d');
  norm.cu = document.getElementById('norm-u').getContext('2d');
  norm.cs = document.getElementById('norm-s').getContext('2d');
  norm.cl = document.getElementById('norm-log').getContext('2d');
  norm.lineBuf = M._malloc(32 * LINE.nlin);
  bul.cu = document.getElementById('bulge-u').getContext('2d');
  for (const el of document.querySelectorAll('select[data-options="joins"]'))
    JOINS.forEach((j, i) => el.add(new Option(JOIN_LABELS[i], j)));
  applyHash();
  syncControls();
  for (const [id, key, conv] of BIND) {
    document.getElementById(id).addEventListener('input', ev => {
      state[key] = conv(ev.target.value);
      if (key === 'shape') state.cp = '';
      document.getElementById('url-msg').textContent = '';
      syncControls(); update([id.split('-')[0]]);
    });
  }
  window.addEventListener('hashchange', () => { applyHash(); syncControls(); update(); });
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

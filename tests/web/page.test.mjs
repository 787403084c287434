// Browser test of dflab's teaching page (build/web), run by `make web-test`
// (part of `make test`): Debian's headless chromium driven by playwright-core.
//
// Checks: the page loads without console errors and fetches only its own
// files; each control changes the picture; u and grad u at 20 points equal
// `dflab probe` on the config the page shows, to 1e-12; the normalization
// orders shown match the bs04 normalization table (dflab run
// bs04_normalization.ini: p, p - 1, <= 6 for the smooth trim); the URL state round-trips; a screenshot of each
// panel is written (DFL_OUT/web-*.png).  With --bench it prints the
// two-segment panel's frame rate instead (`make bench`).
//
// Environment: DFL_WEB (the built page), DFL_DFLAB (the native CLI),
// DFL_OUT (where screenshots and probe files go), DFL_CHROMIUM (default
// /usr/bin/chromium).
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { chromium } from 'playwright-core';

const WEB = process.env.DFL_WEB, DFLAB = process.env.DFL_DFLAB, OUT = process.env.DFL_OUT;
const CHROMIUM = process.env.DFL_CHROMIUM || '/usr/bin/chromium';
const BENCH = process.argv.includes('--bench');
for (const [k, v] of [['DFL_WEB', WEB], ['DFL_OUT', OUT]].concat(BENCH ? [] : [['DFL_DFLAB', DFLAB]]))
  if (!v) { console.error(`page.test: ${k} is not set`); process.exit(2); }
for (const f of [path.join(WEB, 'index.html'), CHROMIUM].concat(BENCH ? [] : [DFLAB]))
  if (!fs.existsSync(f)) { console.error(`page.test: ${f} is missing (make deps; make web)`); process.exit(2); }
fs.mkdirSync(OUT, { recursive: true });

let failures = 0, passes = 0;
function check(ok, what) {
  if (ok) { passes++; console.log(`  ok   ${what}`); }
  else { failures++; console.log(`  FAIL ${what}`); }
}

// A static server for the page's folder only.
const TYPES = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css', '.wasm': 'application/wasm' };
const requests = [];
const server = http.createServer((req, res) => {
  requests.push(req.url);
  const rel = decodeURIComponent(req.url.split('?')[0]).replace(/^\/+/, '') || 'index.html';
  const file = path.join(WEB, rel);
  if (!file.startsWith(WEB) || !fs.existsSync(file) || fs.statSync(file).isDirectory()) {
    res.writeHead(404); res.end('not found'); return;
  }
  res.writeHead(200, { 'Content-Type': TYPES[path.extname(file)] || 'application/octet-stream' });
  fs.createReadStream(file).pipe(res);
});
await new Promise(r => server.listen(0, '127.0.0.1', r));
const BASE = `http://127.0.0.1:${server.address().port}/`;

const browser = await chromium.launch({
  executablePath: CHROMIUM,
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
         '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
const context = await browser.newContext({ viewport: { width: 1200, height: 900 } });
const page = await context.newPage();
const consoleErrors = [], foreign = [];
page.on('console', m => { if (m.type() === 'error' || m.type() === 'warning') consoleErrors.push(m.text()); });
page.on('pageerror', e => consoleErrors.push(String(e)));
page.on('request', r => { if (!r.url().startsWith(BASE) && !r.url().startsWith('data:')) foreign.push(r.url()); });

async function open(hash) {
  await page.goto('about:blank');
  await page.goto(BASE + 'index.html' + hash);
  await page.waitForSelector('#status[data-ready="1"]', { timeout: 30000 });
}
const pixels = id => page.evaluate(i => document.getElementById(i).toDataURL(), id);

try {
  if (BENCH) {
    await open('');
    await page.evaluate(() => window.dflab.bench(5));
    const fps = await page.evaluate(() => window.dflab.bench(60));
    const size = fs.statSync(path.join(WEB, 'dflab.wasm')).size;
    console.log(`web: two-segment panel at 256^2 (field, exact distance, both maps): ${fps.toFixed(1)} frames/s; dflab.wasm ${size} bytes`);
    fs.writeFileSync(path.join(OUT, 'web_bench.txt'), `fps ${fps.toFixed(2)}\nwasm_bytes ${size}\n`);
  } else {
    console.log('page.test: teaching page in headless chromium');
    // 1. Load with a URL state; controls show it.
    await open('#alpha=120&p=7&trim=strip');
    const st = await page.evaluate(() => window.dflab.state());
    check(st.p === 7 && st.alpha === 120 && st.trim === 'strip', 'URL state #p=7&alpha=120&trim=strip reaches the state');
    check(await page.inputValue('#two-p') === '7' && await page.inputValue('#two-trim') === 'strip',
          'the controls show the URL state');
    check(await page.evaluate(() => location.hash) === '#p=7&trim=strip', 'the URL is kept canonical (defaults dropped)');

    // 2. Each control changes the picture (keyboard for the sliders and selects).
    const controls = [
      ['#two-p', 'two-u', 'ArrowRight'], ['#two-alpha', 'two-u', 'ArrowLeft'], ['#two-join', 'two-u', 'ArrowDown'],
      ['#two-trim', 'two-g', 'ArrowDown'], ['#two-view', 'two-u', 'ArrowDown'],
      ['#two-delta', 'two-u', 'ArrowRight'], ['#two-p2', 'two-u2', 'ArrowLeft'], ['#two-view', 'two-bar', 'ArrowUp'],
      ['#norm-p', 'norm-u', 'ArrowRight'], ['#norm-join', 'norm-u', 'ArrowDown'], ['#norm-trim', 'norm-u', 'ArrowDown'],
      ['#norm-seg', 'norm-u', 'ArrowRight'], ['#norm-t', 'norm-u', 'ArrowRight'],
      ['#norm-t', 'norm-s', 'ArrowRight'], ['#norm-p', 'norm-log', 'ArrowRight'],
      ['#bulge-shape', 'bulge-u', 'ArrowDown'], ['#bulge-eps', 'bulge-u', 'ArrowDown'], ['#bulge-p', 'bulge-u', 'ArrowRight'],
    ];
    for (const [sel, canvas, key] of controls) {
      const before = await pixels(canvas), h0 = await page.evaluate(() => location.hash);
      await page.focus(sel);
      await page.keyboard.press(key);
      const after = await pixels(canvas), h1 = await page.evaluate(() => location.hash);
      check(before !== after && h0 !== h1, `keyboard on ${sel} changes ${canvas} and the URL (${h1})`);
    }
    const bd = await pixels('bulge-u');
    // drag the W's middle peak control point (0.5, 0.75): the page maps [-0.1, 1.1]
    await open('');
    await page.locator('#bulge-u').scrollIntoViewIfNeeded();
    const box = await page.locator('#bulge-u').boundingBox();
    const b0 = await pixels('bulge-u');
    const P = (x, y) => [box.x + (x + 0.1) / 1.2 * box.width, box.y + (1.1 - y) / 1.2 * box.height];
    const [sx, sy] = P(0.5, 0.75), [ex, ey] = P(0.5, 0.55);
    await page.mouse.move(sx, sy); await page.mouse.down(); await page.mouse.move(ex, ey, { steps: 3 }); await page.mouse.up();
    const b1 = await pixels('bulge-u');
    check(b0 !== b1 && bd !== b1 && (await page.evaluate(() => location.hash)).includes('cp='),
          'dragging a control point of the curve changes the picture and the URL');

    // 3. u and grad u at 20 points equal dflab probe on the page's config.
    await open('#alpha=120&p=7&trim=strip');
    const pts = [];
    for (let i = 0; i < 20; i++) pts.push([0.03 + 0.047 * i, 0.95 - 0.043 * ((7 * i) % 20)]);
    const mine = await page.evaluate(p => window.dflab.probe(p), pts);
    for (const [hash, name] of [['#alpha=120&p=7&trim=strip', 'requiv p=7 strip'],
                                ['#alpha=77&p=3&join=rconj&trim=disk_smooth', 'rconj p=3 smooth disk'],
                                ['#alpha=200&p=12&join=requiv_corrected', 'corrected p=12 disk']]) {
      await open(hash);
      const got = await page.evaluate(p => window.dflab.probe(p), pts);
      const ini = await page.evaluate(() => window.dflab.ini('two'));
      const cfg = path.join(OUT, 'web_probe.ini'), csv = path.join(OUT, 'web_points.csv');
      fs.writeFileSync(cfg, ini);
      fs.writeFileSync(csv, 'x,y\n' + pts.map(p => p.join(',')).join('\n') + '\n');
      const r = spawnSync(DFLAB, ['probe', cfg, '--points', csv], { encoding: 'utf8' });
      check(r.status === 0, `dflab probe runs on the page's config (${name})${r.status ? ': ' + r.stderr.trim() : ''}`);
      if (r.status !== 0) continue;
      const rows = r.stdout.trim().split('\n').slice(1).map(l => l.split(',').map(Number));
      let worst = 0;
      rows.forEach((row, i) => {
        for (const [a, b] of [[got[i][0], row[3]], [got[i][1], row[4]], [got[i][2], row[5]]])
          worst = Math.max(worst, Math.abs(a - b) / Math.max(1, Math.abs(b)));
      });
      check(rows.length === 20 && worst <= 1e-12, `page u, grad u = dflab probe at 20 points (${name}): max diff ${worst.toExponential(2)}`);
    }
    check(mine.length === 20, 'probe hook answers 20 points');

    // 4. Normalization orders shown = the bs04 normalization table that
    // `dflab run configs/paper/bs04/bs04_normalization.ini` writes.
    const tdir = path.join(OUT, 'bs04_normalization');
    const cfgPath = path.join(path.dirname(path.dirname(path.dirname(new URL(import.meta.url).pathname))),
                              'configs', 'paper', 'bs04', 'bs04_normalization.ini');
    const run = spawnSync(DFLAB, ['run', cfgPath, '--out', tdir, '--quiet', '--threads', '1'], { encoding: 'utf8' });
    check(run.status === 0, `dflab run bs04_normalization.ini${run.status ? ': ' + run.stderr.trim() : ''}`);
    const lines = fs.readFileSync(path.join(tdir, 'bs04_normalization.csv'), 'utf8').trim().split('\n');
    const head = lines[0].split(','), col = n => head.indexOf(n);
    const table = lines.slice(1).map(l => l.split(',')).map(c => ({
      join: c[col('join')], p: Number(c[col('p')]), trim: c[col('trim')],
      status: c[col('status')], theory: c[col('order_theory')], measured: c[col('measured_order')] }));
    check(table.length === 108, `the table has 3 joins x 12 p x 3 trims (${table.length} rows)`);
    let bad = [];
    for (const row of table) {
      const { join, p, trim } = row;
      await page.evaluate(h => { location.hash = h; }, `#np=${p}&njoin=${join}&ntrim=${trim}`);
      await page.waitForFunction(([p, j, t]) => { const s = window.dflab.state(); return s.np === p && s.njoin === j && s.ntrim === t; }, [p, join, trim]);
      const o = await page.evaluate(() => ({ ...document.getElementById('norm-order').dataset }));
      const want = row.status === 'ok' ? [row.measured, row.theory] : ['n/a', 'n/a'];
      if (o.order !== want[0] || o.theory !== want[1])
        bad.push(`${join} p=${p} ${trim}: page ${o.order} (says ${o.theory}), table ${want[0]} (theory ${want[1]})`);
    }
    check(bad.length === 0, `orders shown (measured and bs04's) for every row match the table${bad.length ? ': ' + bad.slice(0, 4).join('; ') : ''}`);
    {
      await page.evaluate(() => { location.hash = '#np=5&njoin=rconj&ntrim=disk&nseg=2&nt=0.35'; });
      await page.waitForFunction(() => window.dflab.state().nseg === 2 && window.dflab.state().np === 5);
      const nrm = await page.evaluate(() => window.dflab.normal());
      const ini = await page.evaluate(() => window.dflab.ini('norm'));
      const cfg = path.join(OUT, 'web_norm.ini'), csv = path.join(OUT, 'web_norm.csv');
      fs.writeFileSync(cfg, ini);
      fs.writeFileSync(csv, `x,y,dx,dy\n${nrm.x[0]},${nrm.x[1]},${nrm.nrm[0]},${nrm.nrm[1]}\n`);
      const r = spawnSync(DFLAB, ['probe', cfg, '--points', csv, '--jet', '13'], { encoding: 'utf8' });
      let worst = Infinity;
      if (r.status === 0) {
        const row = r.stdout.trim().split('\n')[1].split(',').map(Number).slice(7);
        worst = 0;
        let fact = 1;
        for (let k = 1; k <= 13; k++) {
          fact *= k;
          worst = Math.max(worst, Math.abs(nrm.d[k - 1] - row[k - 1]) / fact * Math.pow(nrm.L, k - 1));
        }
      }
      check(worst <= 1e-12, `d1..d13 shown = dflab probe --jet 13 (scaled |d_k/k!| L^(k-1) diff ${worst})`);
    }

    // 4b. The curve's bulge = the bs04_bulging table (case W_fig2: the W, eps 1e-3,
    // strip trims, delta 0.05) for p = 3.
    {
      const bdir = path.join(OUT, 'bs04_bulging');
      const bcfg = path.join(path.dirname(cfgPath), 'bs04_bulging.ini');
      const br = spawnSync(DFLAB, ['run', bcfg, '--set', 'study.p=3', '--out', bdir, '--quiet'], { encoding: 'utf8' });
      check(br.status === 0, `dflab run bs04_bulging.ini --set study.p=3${br.status ? ': ' + br.stderr.trim() : ''}`);
      const bl = fs.readFileSync(path.join(bdir, 'bs04_bulging.csv'), 'utf8').trim().split('\n');
      const bh = bl[0].split(','), bc = n => bh.indexOf(n);
      const row = bl.slice(1).map(l => l.split(',')).find(c => c[bc('case')] === 'W_fig2' && Number(c[bc('delta')]) === 0.05);
      await open('#eps=0.001&bp=3');
      const pb = Number(await page.getAttribute('#bulge-m', 'data-bulge'));
      const pj = Number(await page.getAttribute('#bulge-m', 'data-joint'));
      const tb = row ? Number(row[bc('bulge_max')]) : NaN, tj = row ? Number(row[bc('bulge_joint_max')]) : NaN;
      check(Math.abs(pb - tb) <= 1e-9 && Math.abs(pj - tj) <= 1e-9,
            `curve bulge shown (max ${pb}, joints ${pj}) = bs04_bulging W_fig2 p=3 delta=0.05 (${tb}, ${tj})`);
    }

    // 5. URL state round-trips: a view set by the controls, reloaded from its URL, is the same view.
    await open('');
    await page.fill('#two-alpha', '150'); await page.dispatchEvent('#two-alpha', 'input');
    await page.selectOption('#two-join', 'rconj');
    await page.fill('#two-p', '5'); await page.dispatchEvent('#two-p', 'input');
    await page.selectOption('#two-trim', 'strip_smooth');
    const url = page.url(), pic = await pixels('two-u'), sx0 = await page.evaluate(() => window.dflab.state());
    check(url.endsWith('#alpha=150&p=5&join=rconj&trim=strip_smooth'), `the controls write the URL (${url.split('#')[1]})`);
    const page2 = await context.newPage();
    page2.on('console', m => { if (m.type() === 'error') consoleErrors.push(m.text()); });
    await page2.goto(url);
    await page2.waitForSelector('#status[data-ready="1"]');
    const pic2 = await page2.evaluate(() => document.getElementById('two-u').toDataURL());
    const sx1 = await page2.evaluate(() => window.dflab.state());
    check(JSON.stringify(sx0) === JSON.stringify(sx1) && pic === pic2 && page2.url() === url,
          'reloading the URL gives the same state, the same picture and the same URL');
    await page2.close();

    // 6. The config button shows the INI.
    await open('#p=7&alpha=120&trim=strip');
    await page.click('#two-config');
    const shown = await page.isVisible('#two-ini');
    const text = await page.textContent('#two-ini');
    check(shown && text.includes('[field]') && text.includes('p = 7') && text.includes('trim = strip'),
          'the config button shows the INI for dflab probe');

    // 6b. Exact segment distances: the joint bulge is bs04's 2^(1/p) - 1 (eq. 6
    // in the hatched sector, where h1 = h2 = |x - v|); no probe config exists.
    await open('#trim=exact&p=4');
    const exPic = await pixels('two-u');
    const bulge = Number(await page.getAttribute('#two-bulge', 'data-bulge'));
    const exIni = await page.evaluate(() => window.dflab.ini('two'));
    await open('#p=4');
    check(exPic !== await pixels('two-u') && Math.abs(bulge - (Math.pow(2, 1 / 4) - 1)) < 1e-9 && exIni.includes('cannot'),
          `trim=exact: joint bulge ${bulge} = 2^(1/4) - 1, and the config says probe cannot build it`);

    // 8. The teacher's items (issue "A researcher's day", item 10).
    // Pixels are read from a copy (willReadFrequently), so that reading them
    // does not make chromium warn about the page's own canvases.
    await page.addInitScript(() => {
      window.__pixels = id => {
        const c = document.getElementById(id), t = document.createElement('canvas');
        t.width = c.width; t.height = c.height;
        const x = t.getContext('2d', { willReadFrequently: true });
        x.drawImage(c, 0, 0);
        return x.getImageData(0, 0, c.width, c.height).data;
      };
    });
    const px = (id, i, j) => page.evaluate(([id, i, j]) => {
      const d = window.__pixels(id), k = 4 * (j * document.getElementById(id).width + i);
      return Array.from(d.slice(k, k + 4));
    }, [id, i, j]);
    const cell = (x, y) => [Math.floor(x * 256), Math.floor((1 - y) * 256)];
    // 8.1 One level delta: u = delta (white) against d = delta (black), the band between them shaded.
    {
      await open('#delta=0.1');
      const st1 = await page.evaluate(() => window.dflab.state());
      // u along the outer bisector (upwards at alpha = 120): where it crosses delta
      const ts = Array.from({ length: 400 }, (_, i) => 0.1 + 0.0005 * i);
      const us = (await page.evaluate(p => window.dflab.probe(p), ts.map(t => [0.5, 0.6 + t]))).map(r => r[0]);
      const tu = ts[us.findIndex(u => u >= 0.1)];
      const [bi, bj] = cell(0.5, 0.6 + (0.1 + tu) / 2), [oi, oj] = cell(0.5, 0.6 + 0.05);
      const inBand = await px('two-u', bi, bj), inside = await px('two-u', oi, oj);
      const orange = c => c[0] > 180 && c[1] < 170 && c[2] < 60;
      const bands = await page.evaluate(() => window.dflab.band());
      check(st1.delta === 0.1 && await page.inputValue('#two-delta') === '0.1' && tu > 0.11 &&
            orange(inBand) && !orange(inside) && bands[0] > 0,
            `delta = 0.1: between d = delta (t = 0.1) and u = delta (t = ${tu}) on the bisector the map is shaded (${inBand}), inside it is not (${inside}); band ${bands[0]} px`);
      const white = await page.evaluate(() => { const d = window.__pixels('two-u');
        let n = 0; for (let k = 0; k < d.length; k += 4) if (d[k] === 255 && d[k + 1] === 255 && d[k + 2] === 255) n++; return n; });
      check(white < 6000, `one level drawn instead of isolines every 0.025 (${white} white pixels)`);
    }
    // 8.8 Side by side: the second map at p2; its band narrows as p grows.
    {
      await open('#p=2&p2=8');
      const [b2, b8] = await page.evaluate(() => window.dflab.band());
      await open('#p=12&p2=1');
      const [b12, b1] = await page.evaluate(() => window.dflab.band());
      await open('#trim=exact&p=3&p2=9');
      const e3 = Number(await page.getAttribute('#two-bulge', 'data-bulge')), e9 = Number(await page.getAttribute('#two-bulge', 'data-bulge2'));
      check(b2 > b8 && b1 > b12 && b8 > 0 && Math.abs(e3 - (2 ** (1 / 3) - 1)) < 1e-9 && Math.abs(e9 - (2 ** (1 / 9) - 1)) < 1e-9 &&
            (await page.textContent('#two-u2-cap')).includes('p₂ = 9'),
            `side-by-side p: band p=2 ${b2} > p2=8 ${b8}, p2=1 ${b1} > p=12 ${b12}; exact bulges ${e3}, ${e9} = 2^(1/p) - 1`);
    }
    // 8.2 The colour bar: its numbers, and a pixel of the map has the bar's colour at its u.
    {
      await open('');
      const bar = await page.evaluate(() => ({ ...document.getElementById('two-bar').dataset, label: document.getElementById('two-bar').getAttribute('aria-label') }));
      const [i, j] = cell(0.75, 0.85), x = (i + 0.5) / 256, y = 1 - (j + 0.5) / 256;
      const u = (await page.evaluate(p => window.dflab.probe(p), [[x, y]]))[0][0];
      const row = Math.round(Number(bar.bottom) - (u - Number(bar.min)) / (Number(bar.max) - Number(bar.min)) * (Number(bar.bottom) - Number(bar.top)));
      const cm = await px('two-u', i, j), cb = await px('two-bar', Math.floor(Number(bar.x)), row);
      const diff = Math.max(...[0, 1, 2].map(k => Math.abs(cm[k] - cb[k])));
      await open('#view=err');
      const ticksErr = await page.getAttribute('#two-bar', 'data-ticks');
      check(bar.ticks === '0,0.1,0.2,0.3,0.4,0.5,0.6' && bar.label.includes('0.6') && u > 0.15 && u < 0.55 && diff <= 6 &&
            ticksErr === '-0.05,-0.025,0,0.025,0.05',
            `colour bar: ticks ${bar.ticks}; map pixel at u = ${u.toFixed(4)} is ${cm}, the bar at that u ${cb}; u − d ticks ${ticksErr}`);
    }
    // 8.3 The legend of the eq. 13-14 plot: each line's colour is drawn in the plot.
    {
      await open('');
      const items = await page.$$eval('#two-b-legend li', ls => ls.map(l => ({ key: l.dataset.key, colour: l.dataset.colour, text: l.textContent })));
      const counts = await page.evaluate(cols => {
        const d = window.__pixels('two-b');
        return cols.map(c => { const r = parseInt(c.slice(1, 3), 16), g = parseInt(c.slice(3, 5), 16), b = parseInt(c.slice(5, 7), 16);
          let n = 0; for (let k = 0; k < d.length; k += 4) if (d[k] === r && d[k + 1] === g && d[k + 2] === b) n++; return n; });
      }, items.map(e => e.colour));
      const text = items.map(e => e.text).join(' | ');
      check(items.length === 4 && text.includes('upper bound') && text.includes('eq. 14') && text.includes('lower bound') &&
            text.includes('eq. 13') && text.includes('measured') && counts.every(n => n >= 20),
            `legend of the bound plot: ${text} (pixels of each colour: ${counts})`);
    }
    // 8.4 The 1D panel: u(s) and d(s) on the normal; |u - d| ~ s^(m+1).
    for (const [np, join] of [[4, 'requiv'], [2, 'requiv'], [5, 'rconj']]) {
      await open(`#np=${np}&njoin=${join}`);
      const L = await page.evaluate(() => window.dflab.line());
      const shown = Number(await page.getAttribute('#norm-order', 'data-order'));
      const pts = L.s.map((s, i) => [Math.log10(s), Math.log10(Math.abs(L.u[i] - L.d[i]))]).filter(([e, g]) => e >= -2.7 && e <= -1.7 && Number.isFinite(g));
      const n = pts.length, mx = pts.reduce((a, p) => a + p[0], 0) / n, my = pts.reduce((a, p) => a + p[1], 0) / n;
      const slope = pts.reduce((a, p) => a + (p[0] - mx) * (p[1] - my), 0) / pts.reduce((a, p) => a + (p[0] - mx) ** 2, 0);
      const m = join === 'rconj' ? np - 1 : np;
      check(L.order === m && shown === m && n >= 30 && Math.abs(slope - (m + 1)) < 0.1 && Math.abs(L.u[0] - L.d[0]) < 1e-4 * L.s[0],
            `normal line, ${join} p=${np} (order ${L.order}, shown ${shown}): |u - d| falls like s^${slope.toFixed(3)} for s in [0.002, 0.02], ` +
            `slope m + 1 = ${m + 1}; |u - d| = ${Math.abs(L.u[0] - L.d[0]).toExponential(2)} at s = ${L.s[0]}`);
    }
    // 8.5 What R-functions are and why normalization matters, on the page.
    {
      const about = await page.textContent('#about');
      check(/R-functions/.test(about) && about.includes('sign') && about.includes('normalized to order m') &&
            about.includes('O(dm+1)') && about.includes('bulge'), 'the page says what R-functions are and why normalization matters');
    }
    // 8.6 The corrected join with exact parts at alpha = 200: the outer bisector is downwards there.
    {
      await open('#alpha=200&join=requiv_corrected&trim=exact');
      const b = Number(await page.getAttribute('#two-bulge', 'data-bulge'));
      const ct = Number(await page.getAttribute('#two-bulge', 'data-convex-t'));
      const txt = await page.textContent('#two-bulge');
      const want = Math.pow(2 * Math.pow(Math.sin(80 * Math.PI / 180), -2) - 1, 0.5) - 1;
      await open('#alpha=200&trim=exact&p=4');
      const b4 = Number(await page.getAttribute('#two-bulge', 'data-bulge'));
      check(Math.abs(b) < 1e-12 && Math.abs(ct - want) < 1e-9 && txt.includes('convex side') && txt.includes('downwards') &&
            Math.abs(b4 - (2 ** 0.25 - 1)) < 1e-9,
            `alpha = 200, corrected, exact parts: bulge ${b} on the reflex-side bisector; upwards (convex side) t/δ - 1 = ${ct} = (2 sin^-2(80°) - 1)^(1/2) - 1, explained; requiv p=4 ${b4}`);
    }
    // 8.7 Invalid URL values are said, not silently replaced.
    {
      await open('#p=abc');
      const m1 = await page.textContent('#url-msg'), v1 = await page.isVisible('#url-msg'), s1 = await page.evaluate(() => window.dflab.state());
      await open('#alpha=999&njoin=nope&zzz=1');
      const m2 = await page.textContent('#url-msg'), s2 = await page.evaluate(() => window.dflab.state());
      const h2 = await page.evaluate(() => location.hash);
      await open('#p=7&alpha=120');
      const m3 = await page.textContent('#url-msg'), v3 = await page.isVisible('#url-msg');
      check(v1 && m1.includes('p=abc') && m1.includes('not a number') && s1.p === 2 &&
            m2.includes('alpha=999') && m2.includes('outside 10…350') && s2.alpha === 350 && m2.includes('njoin=nope') &&
            m2.includes('unknown key') && h2 === '#alpha=350' && m3 === '' && !v3,
            `invalid URL values are shown: "${m1}" / "${m2}"; a valid URL shows nothing`);
    }

    // 7. Screenshots of each panel.
    await page.click('#norm-u', { position: { x: 100, y: 150 } });
    for (const id of ['two', 'norm', 'bulge']) {
      const f = path.join(OUT, `web-${id}.png`);
      await page.locator('#' + id).screenshot({ path: f });
      check(fs.existsSync(f) && fs.statSync(f).size > 10000, `screenshot ${f}`);
    }
    await page.screenshot({ path: path.join(OUT, 'web-page.png'), fullPage: true });

    check(consoleErrors.length === 0, `no console errors or warnings${consoleErrors.length ? ': ' + consoleErrors.slice(0, 3).join(' | ') : ''}`);
    check(foreign.length === 0, `the page fetches only its own files${foreign.length ? ': ' + foreign.slice(0, 3).join(' ') : ''}`);
    const own = [...new Set(requests.map(u => u.split('?')[0]))].sort();
    check(own.every(u => ['/index.html', '/app.js', '/dflab.js', '/style.css'].includes(u)),
          `requests: ${own.join(' ')}`);
  }
} catch (e) {
  failures++;
  console.log(`  FAIL ${e && e.stack ? e.stack : e}`);
} finally {
  await browser.close();
  server.close();
}
if (!BENCH) console.log(`page.test: Synthesis: Tested: ${passes + failures} | Passing: ${passes} | Failing: ${failures}`);
process.exit(failures ? 1 : 0);

// The HTML thickness report in a real browser: Debian's headless Chromium driven by
// playwright-core (viewer/node_modules), WebGL by SwiftShader (software, no GPU).
//
//   node html_report_browser.mjs --bemshape BIN --sample BIN --viewer DIR --plate STL --out DIR
//        [--sizes 100000,1000000] [--screenshots DIR [--docs-region K]] [--max-edge 40]
//        [--damaged NAME --make-test-mesh BIN]
//
// For each report (a real `bemshape thickness --html` run on the bundled plate, checked
// against the same run's --report JSON, the same plate at a limit larger than the plate,
// whose page must show the units warning, and a synthetic part written by
// make_html_report_sample), opened from file://:
//   * the units warning line under the verdict where the run warned, none elsewhere;
//   * no console error and no page error while it loads, renders and flies;
//   * the verdict, the histogram (one bar per bin of the report) and the region list are in
//     the DOM;
//   * the canvas is not blank: many distinct colours, most of the view covered by the part;
//   * clicking the first region changes a substantial part of the picture, selects the
//     region and shows the marker (its colour appears where it did not before).
// Prints the file size and the time to first render of each report. --sizes adds synthetic
// reports of those face counts (measurements, not part of ctest); --screenshots DIR keeps
// the plate's overview and region pictures there (docs/images; the region picture after
// clicking region K + 1 when --docs-region K is given).
import { execFileSync, spawnSync } from 'node:child_process';
import { mkdirSync, readFileSync, statSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const args = {};
for (let i = 2; i < process.argv.length; i += 2) args[process.argv[i].replace(/^--/, '')] = process.argv[i + 1];
for (const required of ['bemshape', 'sample', 'viewer', 'plate', 'out'])
  if (!args[required]) throw new Error(`--${required} is required`);
mkdirSync(args.out, { recursive: true });

const { chromium } = createRequire(path.resolve(args.viewer, 'package.json'))('playwright-core');

// SwiftShader gives WebGL without a GPU; Chromium 117+ asks for --enable-unsafe-swiftshader
// before it falls back to it. The other flags keep the browser off the network and quiet.
const chromiumArgs = [
  '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync',
  '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
];

let failures = 0;
function check(condition, what) {
  console.log(`${condition ? 'ok  ' : 'FAIL'} ${what}`);
  if (!condition) failures += 1;
}

function megabytes(file) {
  return (statSync(file).size / 1e6).toFixed(2);
}

/// Pixel statistics of a PNG screenshot, computed in the page (the browser decodes PNG):
/// distinct colours (6 bits per channel), fraction differing from the background, fraction
/// of the marker's colour; with a second PNG, the fraction of pixels that differ.
async function pixelStats(page, png, other) {
  return page.evaluate(async ([a, b]) => {
    const decode = async (base64) => {
      const bitmap = await createImageBitmap(await (await fetch(`data:image/png;base64,${base64}`)).blob());
      const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
      const context = canvas.getContext('2d');
      context.drawImage(bitmap, 0, 0);
      return context.getImageData(0, 0, bitmap.width, bitmap.height).data;
    };
    const p = await decode(a);
    const q = b ? await decode(b) : null;
    const colours = new Set();
    let foreground = 0, marker = 0, differ = 0;
    const n = p.length / 4;
    for (let i = 0; i < p.length; i += 4) {
      const [r, g, bl] = [p[i], p[i + 1], p[i + 2]];
      colours.add(((r >> 2) << 12) | ((g >> 2) << 6) | (bl >> 2));
      if (Math.abs(r - 0xee) + Math.abs(g - 0xf1) + Math.abs(bl - 0xf4) > 12) foreground += 1;
      if (r > 200 && g < 90 && bl > 50 && bl < 140) marker += 1;  // #ff2d55 and its shades
      if (q && Math.abs(r - q[i]) + Math.abs(g - q[i + 1]) + Math.abs(bl - q[i + 2]) > 24) differ += 1;
    }
    return { colours: colours.size, foreground: foreground / n, marker: marker / n, differ: differ / n };
  }, [png.toString('base64'), other ? other.toString('base64') : null]);
}

async function checkReport(browser, file, name, expect) {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  const errors = [];
  page.on('console', (message) => { if (message.type() === 'error') errors.push(message.text()); });
  page.on('pageerror', (error) => errors.push(String(error)));
  page.on('request', (request) => {
    const url = request.url();
    if (!url.startsWith('file:') && !url.startsWith('data:') && !url.startsWith('blob:')) errors.push(`network request ${url}`);
  });
  const began = Date.now();
  await page.goto(pathToFileURL(file).href);
  await page.waitForFunction(() => window.bemshapeViewer && (window.bemshapeViewer.ready || window.bemshapeViewer.error), null, { timeout: 120000 });
  const state = await page.evaluate(() => ({ ...window.bemshapeViewer, renderer: (() => {
    const gl = document.querySelector('canvas').getContext('webgl2');
    const info = gl && gl.getExtension('WEBGL_debug_renderer_info');
    return info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : 'unknown';
  })() }));
  check(!state.error, `${name}: page reports no error (${state.error || 'none'})`);
  const firstRender = state.timings.firstRender;
  console.log(`     ${name}: ${megabytes(file)} MB, first render ${firstRender.toFixed(0)} ms after navigation ` +
              `(decode ${state.timings.decode.toFixed(0)} ms, build ${state.timings.build.toFixed(0)} ms; ` +
              `wall ${Date.now() - began} ms), WebGL renderer: ${state.renderer}`);

  const verdict = await page.textContent('#verdict');
  check(verdict.startsWith(expect.verdict), `${name}: verdict "${verdict}"`);
  const bars = await page.locator('#histogram-chart rect.bar').count();
  check(bars === expect.bins && bars > 0, `${name}: histogram has ${bars} bars (report: ${expect.bins})`);
  const regions = await page.locator('#regions button.region').count();
  check(regions === expect.regions && regions > 0, `${name}: ${regions} regions listed (report: ${expect.regions})`);
  check((await page.locator('#parameters tr').count()) > 0, `${name}: parameters table filled`);
  const warnings = await page.locator('#warnings p').allTextContents();
  check(expect.warning ? warnings.length === 1 && warnings[0].includes(expect.warning) : warnings.length === 0,
        `${name}: warnings shown ${JSON.stringify(warnings)} (expected: ${expect.warning || 'none'})`);

  // Pixel checks on the 3D view alone (the panel's selected button has the marker's colour).
  const overview = await page.screenshot();
  const overviewView = await page.locator('#view').screenshot();
  const before = await pixelStats(page, overviewView);
  check(before.colours > 50, `${name}: overview shows ${before.colours} distinct colours`);
  check(before.foreground > 0.15, `${name}: ${(100 * before.foreground).toFixed(0)} % of the view differs from the background`);

  await page.click('#regions button.region >> nth=0');
  await page.waitForFunction(() => window.bemshapeViewer.selected === 0 && !window.bemshapeViewer.flying, null, { timeout: 30000 });
  console.log(`     ${name}: region 1 (${expect.regionFaces} faces) prepared in ${(await page.evaluate(() => window.bemshapeViewer.timings.select)).toFixed(0)} ms`);
  const region = await page.screenshot();
  const after = await pixelStats(page, await page.locator('#view').screenshot(), overviewView);
  check(after.differ > 0.1, `${name}: clicking region 1 changes ${(100 * after.differ).toFixed(0)} % of the pixels`);
  check(after.marker > before.marker + 1e-4, `${name}: marker and highlight shown (${(100 * before.marker).toFixed(2)} % -> ${(100 * after.marker).toFixed(2)} % of the pixels in the marker colour)`);
  check(await page.locator('#regions button.region.selected').count() === 1, `${name}: the clicked region is marked selected`);
  let docsRegion = region;
  if (expect.docsRegion !== undefined) {
    await page.click(`#regions button.region >> nth=${expect.docsRegion}`);
    await page.waitForFunction((i) => window.bemshapeViewer.selected === i && !window.bemshapeViewer.flying, expect.docsRegion, { timeout: 30000 });
    docsRegion = await page.screenshot();
  }
  check(errors.length === 0, `${name}: no console or page errors${errors.length ? ': ' + errors.join(' | ') : ''}`);
  await page.close();
  return { overview, region: docsRegion, firstRender };
}

const started = Date.now();
const plateHtml = path.join(args.out, 'plate_holes.html');
const plateJson = path.join(args.out, 'plate_holes.json');
// --max-edge 40 (1076 solver faces, dense solver) keeps the run near 10 s on two cores;
// docs/usage.md's session and pictures use --max-edge 20 (1828 faces).
const run = spawnSync(args.bemshape, ['thickness', args.plate, '--h0', '12.7', '--max-edge', args['max-edge'] || '40', '--sharp-angle', '30',
  '--min-thickness', '10', '--html', plateHtml, '--report', plateJson, '--quiet'], { encoding: 'utf8' });
check(run.status === 1, `plate: bemshape thickness --html exits 1 (thin walls found), got ${run.status} ${run.stderr}`);
const plateReport = JSON.parse(readFileSync(plateJson, 'utf8'));
console.log(`     plate: bemshape thickness took ${((Date.now() - started) / 1000).toFixed(1)} s`);
// The page's JSON must hold what the run's JSON report says.
const embedded = JSON.parse(/id="bemshape-report">(.*?)<\/script>/s.exec(readFileSync(plateHtml, 'utf8'))[1]);
const embeddedThin = embedded.regions.filter((r) => r.kind === 'thin');
const embeddedSpecks = embedded.regions.filter((r) => r.kind === 'speck');
check(embeddedThin.length === plateReport.check.regions.length, `plate: ${embeddedThin.length} regions embedded, ${plateReport.check.regions.length} in the JSON report`);
check(embeddedThin.every((r, i) => r.extreme === plateReport.check.regions[i].min && r.area === plateReport.check.regions[i].area),
      'plate: region minima and areas equal the JSON report\'s');
check(embeddedSpecks.length === plateReport.check.specks.length, `plate: ${embeddedSpecks.length} specks embedded, ${plateReport.check.specks.length} in the JSON report`);
check(plateReport.units_warning === null, `plate: no units warning (${plateReport.units_warning})`);
check(embedded.faces === plateReport.mesh.solver_faces, `plate: the solver mesh (${embedded.faces} faces) is shown`);
const histogramArea = embedded.histogram.area.reduce((a, b) => a + b, 0) + embedded.histogram.other_area;
const solverArea = plateReport.thickness.measured_area + plateReport.thickness.unmeasurable_area;
check(Math.abs(histogramArea - solverArea) < 1e-9 * solverArea,
      `plate: histogram areas add up to the solver surface's area (${histogramArea.toFixed(3)} vs ${solverArea.toFixed(3)})`);

const reports = [{ file: plateHtml, name: 'plate', expect: { verdict: 'FAIL', bins: embedded.histogram.area.length, regions: embedded.regions.length, regionFaces: embedded.regions[0]?.face_count,
                                                              docsRegion: args['docs-region'] !== undefined ? Number(args['docs-region']) : undefined } }];
// The same plate checked at a limit larger than the plate is thick over its whole surface:
// FAIL, and the units warning on the page.
const unitsHtml = path.join(args.out, 'plate_units.html');
const unitsJson = path.join(args.out, 'plate_units.json');
const unitsRun = spawnSync(args.bemshape, ['thickness', args.plate, '--h0', '12.7', '--max-edge', args['max-edge'] || '40', '--sharp-angle', '30',
  '--min-thickness', '1000', '--html', unitsHtml, '--report', unitsJson, '--quiet'], { encoding: 'utf8' });
check(unitsRun.status === 1, `plate at 1000: exits 1, got ${unitsRun.status} ${unitsRun.stderr}`);
const unitsReport = JSON.parse(readFileSync(unitsJson, 'utf8'));
check(typeof unitsReport.units_warning === 'string' && unitsReport.units_warning.startsWith('units: --min-thickness 1000'),
      `plate at 1000: the JSON report warns (${unitsReport.units_warning})`);
const unitsEmbedded = JSON.parse(/id="bemshape-report">(.*?)<\/script>/s.exec(readFileSync(unitsHtml, 'utf8'))[1]);
reports.push({ file: unitsHtml, name: 'plate at 1000', expect: { verdict: 'FAIL', bins: unitsEmbedded.histogram.area.length, regions: unitsEmbedded.regions.length,
                                                                  regionFaces: unitsEmbedded.regions[0]?.face_count, warning: unitsReport.units_warning } });
const sizes = [10000, ...(args.sizes ? args.sizes.split(',').map(Number) : [])];
for (const faces of sizes) {
  const file = path.join(args.out, `sample_${faces}.html`);
  const t = Date.now();
  execFileSync(args.sample, [String(faces), file]);
  const meta = JSON.parse(/id="bemshape-report">(.*?)<\/script>/s.exec(readFileSync(file, 'utf8'))[1]);
  console.log(`     synthetic ${meta.faces} faces: written in ${Date.now() - t} ms`);
  reports.push({ file, name: `synthetic ${meta.faces} faces`, expect: { verdict: 'FAIL', bins: meta.histogram.area.length, regions: meta.regions.length, regionFaces: meta.regions[0]?.face_count } });
}

// A part that crosses itself where no solid can be recovered (--damaged NAME of the
// damaged-mesh corpus, written by --make-test-mesh BIN): measured as given, the page must
// list the region and draw the faces its JSON report marks in the defect colour.
let damaged = null;
if (args.damaged) {
  const stl = path.join(args.out, `${args.damaged}.stl`);
  execFileSync(args['make-test-mesh'], ['damaged', args.damaged, stl]);
  const html = path.join(args.out, 'damaged.html'), json = path.join(args.out, 'damaged.json');
  const r = spawnSync(args.bemshape, ['thickness', stl, '--h0', '0.5', '--max-edge', '0.35', '--html', html, '--report', json, '--quiet'], { encoding: 'utf8' });
  check(r.status === 0, `damaged: bemshape thickness exits 0, got ${r.status} ${r.stderr}`);
  check(/warning: .*crosses itself in 1 region/.test(r.stderr), 'damaged: the warning goes to stderr');
  damaged = { html, report: JSON.parse(readFileSync(json, 'utf8')) };
}

async function checkDamaged(browser) {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  const errors = [];
  page.on('console', (message) => { if (message.type() === 'error') errors.push(message.text()); });
  page.on('pageerror', (error) => errors.push(String(error)));
  await page.goto(pathToFileURL(damaged.html).href);
  await page.waitForFunction(() => window.bemshapeViewer && (window.bemshapeViewer.ready || window.bemshapeViewer.error), null, { timeout: 120000 });
  const state = await page.evaluate(() => ({ error: window.bemshapeViewer.error, defectFaces: window.bemshapeViewer.defectFaces }));
  check(!state.error, `damaged: page reports no error (${state.error || 'none'})`);
  const marked = damaged.report.defects.reduce((n, d) => n + d.solver_faces_marked, 0);
  check(state.defectFaces > 0 && state.defectFaces === marked, `damaged: ${state.defectFaces} faces drawn in the defect colour, ${marked} marked in the JSON report`);
  check(await page.isVisible('#defects'), 'damaged: the defect warning is shown');
  const text = await page.textContent('#defects');
  check(text.includes('crosses itself') && text.includes('across around'), `damaged: the warning names the region and its size ("${text.slice(0, 120)}...")`);
  // kDefectColour (230, 0, 180), shaded by nothing (an unlit overlay at 0.75 opacity).
  const shot = (await page.locator('#view').screenshot()).toString('base64');
  const magenta = await page.evaluate(async (a) => {
    const bitmap = await createImageBitmap(await (await fetch(`data:image/png;base64,${a}`)).blob());
    const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
    const context = canvas.getContext('2d');
    context.drawImage(bitmap, 0, 0);
    const p = context.getImageData(0, 0, bitmap.width, bitmap.height).data;
    let n = 0;
    for (let i = 0; i < p.length; i += 4) if (p[i] > 150 && p[i + 1] < 80 && p[i + 2] > 110) n += 1;
    return n / (p.length / 4);
  }, shot);
  check(magenta > 1e-3, `damaged: ${(100 * magenta).toFixed(2)} % of the view in the defect colour`);
  check(errors.length === 0, `damaged: no console or page errors${errors.length ? ': ' + errors.join(' | ') : ''}`);
  await page.close();
}

const browser = await chromium.launch({ executablePath: process.env.BEMSHAPE_CHROMIUM || '/usr/bin/chromium', args: chromiumArgs, headless: true });
try {
  if (damaged) await checkDamaged(browser);
  for (const r of reports) {
    const shots = await checkReport(browser, r.file, r.name, r.expect);
    if (r.name === 'plate' && args.screenshots) {
      mkdirSync(args.screenshots, { recursive: true });
      writeFileSync(path.join(args.screenshots, 'html_report_overview.png'), shots.overview);
      writeFileSync(path.join(args.screenshots, 'html_report_region.png'), shots.region);
    }
    writeFileSync(path.join(args.out, `${path.basename(r.file, '.html')}_overview.png`), shots.overview);
    writeFileSync(path.join(args.out, `${path.basename(r.file, '.html')}_region.png`), shots.region);
  }
} finally {
  await browser.close();
}
console.log(`     total ${((Date.now() - started) / 1000).toFixed(1)} s`);
console.log(`${failures === 0 ? 'all checks passed' : `${failures} checks failed`}`);
process.exit(failures === 0 ? 0 : 1);

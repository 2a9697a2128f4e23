// The web page in a real browser (Debian's headless chromium, driven by playwright-core),
// checked against the command line: web/test.sh builds both and runs this.
//
//   node test/e2e.mjs [--screenshot FILE] [--bench]
//
// It serves web/dist/ on localhost with Python's static server and checks that
//   1. two examples render on the canvas with the command line's bytes (same scene, size),
//      and download as its files;
//   2. an edit during a long render cancels it;
//   3. an error typed into a scene shows the command line's message, its line marked;
//   4. a texture not added is the command line's error, and once added it renders;
//   5. a clicked pixel shows the command line's trace, whose final bytes are the canvas's;
//   6. a dropped image made with a known mistake (--variant) gets the command line's
//      compare report, which names that variant, and a diff image over the canvas;
//   7. a student's own debug trace pasted beside a clicked pixel gets `trace --against`'s
//      report: the planted first difference, agreement, or the refusal of another pixel;
//      a whole image's trace gets `trace --against FILE W H`'s summary, whose pixels trace
//      when clicked;
//  10. a pixel typed as X and Y is traced (at any size the canvas is shown), and the
//      pixels a compare report names trace when clicked;
//  11. opened from disk (file://), the page says to serve it with web/serve.sh;
//  12. the sizes docs/web.md gives for web/dist/ are those of the folder built;
//   8. `legacy-rt grade`'s report (index.html), opened from disk: no console error, every
//      image loads, no request leaves the disk;
//   9. at 1366x900 and 390x844 nothing is cut at the right, every control is labelled, and
//      on a phone the image comes first and a tapped pixel's trace is scrolled into view.
// --screenshot FILE saves the page with a traced pixel (docs/web-page.png is one);
// --grade-screenshot FILE the top of grade's report (docs/grade-report.png);
// --phone-screenshot FILE the page at 390x844 with a compared image (docs/web-phone.png).
// --bench times 640x480 renders of the course scenes in the page's worker (the render
// call alone) against the native binary on one thread (target/release/legacy-rt, CPU
// time of the whole run, loading included), medians of 5, alternated run by run.

import { spawn, spawnSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, readFileSync, readdirSync, rmSync, statSync, writeFileSync, existsSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import assert from 'node:assert/strict';
import { chromium } from 'playwright-core';

const web = join(dirname(fileURLToPath(import.meta.url)), '..');
const top = join(web, '..');
const args = process.argv.slice(2);
const screenshot = args.includes('--screenshot') ? args[args.indexOf('--screenshot') + 1] : null;
const bench = args.includes('--bench');
const phoneScreenshot = args.includes('--phone-screenshot')
  ? args[args.indexOf('--phone-screenshot') + 1] : null;
const gradeScreenshot = args.includes('--grade-screenshot')
  ? args[args.indexOf('--grade-screenshot') + 1] : null;
const binary = process.env.LEGACY_RT ?? join(top, 'target/debug/legacy-rt');
// The files the test writes (images made by the command line, downloads); removed at the end.
const scratch = mkdtempSync(join(tmpdir(), 'legacy-rt-web-'));

// ---- The command line.

function legacyRt(argv, { input = '', cwd = top } = {}) {
  const run = spawnSync(binary, argv, { input, cwd, maxBuffer: 1 << 28 });
  if (run.error) throw run.error;
  return { status: run.status, stdout: run.stdout, stderr: run.stderr.toString() };
}

// The RGB bytes of a binary PPM as the command line writes it (`P6 W H 255\n`).
function ppmPixels(bytes) {
  const header = bytes.subarray(0, 40).toString('latin1').match(/^P6 (\d+) (\d+) 255\n/);
  assert.ok(header, 'a P6 header');
  return { width: +header[1], height: +header[2], rgb: bytes.subarray(header[0].length) };
}

// ---- The page.

function serve() {
  return new Promise((resolve, reject) => {
    const server = spawn('python3', ['-u', '-m', 'http.server', '0', '--bind', '127.0.0.1',
      '--directory', join(web, 'dist')], { stdio: ['ignore', 'pipe', 'ignore'] });
    server.on('error', reject);
    server.stdout.on('data', (chunk) => {
      const port = chunk.toString().match(/port (\d+)/);
      if (port) resolve({ server, url: `http://127.0.0.1:${port[1]}/` });
    });
  });
}

const FLAGS = ['--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking',
  '--disable-component-update', '--no-first-run'];

async function settled(page) {
  await page.waitForFunction(() => ['done', 'error'].includes(document.body.dataset.state),
    null, { timeout: 60_000 });
  return page.evaluate(() => document.body.dataset.state);
}

// Edits a control the way a user does (it fires `input`) and waits for the new render.
async function setAndRender(page, selector, value) {
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  await page.fill(selector, value);
  return settled(page);
}

async function canvasPixels(page) {
  return page.evaluate(() => {
    const canvas = document.getElementById('image');
    const data = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
    const rgb = [];
    for (let i = 0; i < data.length; i += 4) rgb.push(data[i], data[i + 1], data[i + 2]);
    return { width: canvas.width, height: canvas.height, rgb };
  });
}

async function openExample(page, name) {
  // Away and back, so that choosing the example shown reloads it too.
  await page.selectOption('#example', '');
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  await page.selectOption('#example', name);
  return settled(page);
}

// 1. The canvas holds the command line's bytes.
async function rendersAsTheCommandLine(page, name, width, height) {
  assert.equal(await openExample(page, name), 'done', name);
  await page.fill('#height', String(height));
  assert.equal(await setAndRender(page, '#width', String(width)), 'done');
  const text = readFileSync(join(top, 'examples', name));
  const cli = legacyRt([String(width), String(height)], { input: text });
  assert.equal(cli.status, 0, cli.stderr);
  const expected = ppmPixels(cli.stdout);
  const shown = await canvasPixels(page);
  assert.deepEqual([shown.width, shown.height], [expected.width, expected.height], name);
  const differing = shown.rgb.filter((byte, i) => byte !== expected.rgb[i]).length;
  assert.equal(differing, 0, `${name}: ${differing} of ${shown.rgb.length} bytes differ`);
  console.log(`ok 1 - ${name} at ${width}x${height}: the canvas is the command line's bytes`);
  // Downloaded as PPM, the file is the command line's; as PNG, the same pixels.
  const save = async (button) => {
    const [download] = await Promise.all([page.waitForEvent('download'), page.click(button)]);
    return { name: download.suggestedFilename(), bytes: readFileSync(await download.path()) };
  };
  const ppm = await save('#download-ppm');
  assert.equal(ppm.name, name.replace('.txt', '.ppm'));
  assert.ok(ppm.bytes.equals(cli.stdout), 'the downloaded PPM is the command line\'s');
  const png = await save('#download-png');
  const folder = scratch;
  writeFileSync(join(folder, 'page.png'), png.bytes);
  writeFileSync(join(folder, 'cli.ppm'), cli.stdout);
  const compared = legacyRt(['compare', '--allow', '0', 'cli.ppm', 'page.png'], { cwd: folder });
  assert.equal(compared.status, 0, compared.stdout.toString() + compared.stderr);
  console.log(`ok 1 - and downloaded: ${ppm.name} is the command line's file, ${png.name} its pixels`);
}

// 1c. In the ambient stage too, where a span's camera rays take the lanes of vector
// registers (src/shapes/mod.rs, `Dirs`): the WebAssembly takes the wide crate's arrays
// there, not the SSE2 registers the command line's tests run on.
async function rendersTheAmbientStageAsTheCommandLine(page, name, width, height) {
  assert.equal(await openExample(page, name), 'done', name);
  await page.fill('#height', String(height));
  assert.equal(await setAndRender(page, '#width', String(width)), 'done');
  const stage = async (value) => {
    await page.evaluate(() => { document.body.dataset.state = 'edited'; });
    await page.selectOption('#stage', value);
    return settled(page);
  };
  assert.equal(await stage('ambient'), 'done');
  const text = readFileSync(join(top, 'examples', name));
  const cli = legacyRt(['--stage', 'ambient', String(width), String(height)], { input: text });
  assert.equal(cli.status, 0, cli.stderr);
  const expected = ppmPixels(cli.stdout);
  const shown = await canvasPixels(page);
  assert.deepEqual([shown.width, shown.height], [expected.width, expected.height], name);
  const differing = shown.rgb.filter((byte, i) => byte !== expected.rgb[i]).length;
  assert.equal(differing, 0, `${name}, ambient stage: ${differing} of ${shown.rgb.length} bytes differ`);
  // Not vacuous: the stage shows something, and not the full render.
  assert.ok(expected.rgb.some((byte) => byte !== 0), `${name}: the ambient stage is black`);
  // The checks that follow expect the full stage.
  assert.equal(await stage('full'), 'done');
  console.log(`ok 1 - ${name} at ${width}x${height} in the ambient stage: the command line's bytes`);
}

// 2. An edit during a long render cancels it (the worker is ended) and renders the new text.
async function cancelsALongRender(page) {
  assert.equal(await openExample(page, 'quadrics_gallery.txt'), 'done');
  const before = await page.evaluate(() => window.legacyRt.renderer.workers);
  await page.fill('#height', '4000');
  await page.fill('#width', '4096');
  await page.waitForFunction(() => document.body.dataset.state === 'rendering');
  await page.fill('#height', '90');
  assert.equal(await setAndRender(page, '#width', '120'), 'done');
  const after = await page.evaluate(() => window.legacyRt.renderer.workers);
  assert.ok(after > before, 'the long render\'s worker was ended');
  const shown = await canvasPixels(page);
  const cli = legacyRt(['120', '90'], { input: readFileSync(join(top, 'examples/quadrics_gallery.txt')) });
  assert.deepEqual(shown.rgb, [...ppmPixels(cli.stdout).rgb]);
  console.log('ok 2 - an edit during a 4096x4000 render cancels it and shows the new image');
}

// 3. An error shows the command line's message, its line marked.
async function showsTheError(page) {
  assert.equal(await openExample(page, 'spheres.txt'), 'done');
  const lines = (await page.inputValue('#scene')).split('\n');
  const line = lines.findIndex((l) => l.includes('radius')) + 1;
  lines[line - 1] = lines[line - 1].replace(/^\S+/, 'two');
  const broken = lines.join('\n');
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  // Typed: the line's first number replaced by a word, key by key.
  await page.fill('#scene', lines.slice(0, line - 1).join('\n') + '\n');
  await page.focus('#scene');
  await page.keyboard.press('Control+End');
  await page.keyboard.type(lines.slice(line - 1).join('\n'), { delay: 0 });
  assert.equal(await page.inputValue('#scene'), broken);
  assert.equal(await settled(page), 'error');
  const cli = legacyRt([], { input: broken });
  assert.equal(cli.status, 1);
  const shown = await page.textContent('#error-text');
  assert.equal(shown, cli.stderr.trimEnd());
  assert.match(shown, new RegExp(`--> line ${line}, column 1`));
  assert.equal(await page.textContent('#gutter .bad'), String(line));
  assert.equal(await page.getAttribute('#error', 'data-line'), String(line));
  console.log(`ok 3 - an error typed on line ${line} is the command line's, line ${line} marked`);
}

// 3b. A size too large is named as typed, not as the preview's quarter of it.
async function namesTheSizeTyped(page) {
  await page.fill('#height', '');
  assert.equal(await setAndRender(page, '#width', '99999'), 'error');
  // A scene just opened is rendered as a quarter-size preview first.
  assert.equal(await openExample(page, 'spheres.txt'), 'error');
  const cli = legacyRt(['99999'], { input: readFileSync(join(top, 'examples', 'spheres.txt')) });
  assert.notEqual(cli.status, 0);
  const shown = await page.textContent('#error-text');
  assert.match(shown, /99999x/, shown);
  assert.doesNotMatch(shown, /25000x/, shown);
  await page.fill('#height', '90');
  assert.equal(await setAndRender(page, '#width', '120'), 'done');
  console.log(`ok 3 - a width of 99999 is named as typed: ${shown.split(' is ')[0]}`);
}

// 3c. A scene pasted over an example is no longer named as the example: not by the
// selector, the trace command or the downloads.
async function namesAPastedScene(page) {
  assert.equal(await openExample(page, 'spheres.txt'), 'done');
  const text = readFileSync(join(top, 'examples', 'shadows.txt'), 'utf8');
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  await page.fill('#scene', text);
  assert.equal(await settled(page), 'done');
  assert.equal(await page.inputValue('#example'), '');
  assert.equal(await page.isVisible('#scene-note'), true);
  const box = await page.locator('#image').boundingBox();
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  await page.click('#image', { position: { x: box.width * 0.5, y: box.height * 0.5 } });
  assert.equal(await settled(page), 'done');
  const command = await page.textContent('#trace-command');
  assert.match(command, /< scene\.txt$/, command);
  const [download] = await Promise.all([page.waitForEvent('download'), page.click('#download-ppm')]);
  assert.equal(download.suggestedFilename(), 'scene.ppm');
  console.log(`ok 3 - a scene pasted over spheres.txt is named scene.txt: ${command}`);
}

// 4. A texture the user has not added is the command line's missing-file error; added (a
// browser has no folders: by its file name), the scene renders as the command line's.
async function takesAddedTextures(page) {
  const name = 'wood-for-the-test.ppm';
  const example = readFileSync(join(top, 'examples/textured_planes.txt'), 'utf8');
  const text = example.replaceAll('examples/textures/colours4x3.ppm', `textures/${name}`);
  await page.selectOption('#example', '');
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  await page.fill('#scene', text);
  assert.equal(await settled(page), 'error');
  const missing = legacyRt(['160', '120'], { input: text });
  assert.equal(missing.status, 1);
  assert.equal(await page.textContent('#error-text'), missing.stderr.trimEnd());
  assert.match(missing.stderr, /No such file or directory/);
  // The command line reads it from textures/ under its folder; the page by its name.
  const texture = readFileSync(join(top, 'examples/textures/colours4x3.ppm'));
  const folder = join(scratch, 'scene');
  mkdirSync(join(folder, 'textures'), { recursive: true });
  writeFileSync(join(folder, 'textures', name), texture);
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  await page.setInputFiles('#add-textures', { name, mimeType: 'image/x-portable-pixmap', buffer: texture });
  assert.equal(await settled(page), 'done');
  assert.match(await page.textContent('#textures'), new RegExp(name));
  await page.fill('#height', '120');
  assert.equal(await setAndRender(page, '#width', '160'), 'done');
  const cli = legacyRt(['160', '120'], { input: text, cwd: folder });
  assert.equal(cli.status, 0, cli.stderr);
  assert.deepEqual((await canvasPixels(page)).rgb, [...ppmPixels(cli.stdout).rgb]);
  console.log('ok 4 - a texture not added is the command line\'s error; added, the scene renders as there');
}

// 5. A clicked pixel's trace is the command line's, and its bytes are the canvas's.
async function tracesAClickedPixel(page, name) {
  assert.equal(await openExample(page, name), 'done');
  const { width, height } = await page.evaluate(() => window.legacyRt.state.full);
  const box = await page.locator('#image').boundingBox();
  // A point on the object in the image's middle band, a third of the way across.
  const at = { x: box.width * 0.45, y: box.height * 0.55 };
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  await page.click('#image', { position: at });
  assert.equal(await settled(page), 'done');
  const [x, y] = (await page.getAttribute('#trace-pane', 'data-pixel')).split(',').map(Number);
  const trace = await page.textContent('#trace');
  const last = trace.trimEnd().split('\n').at(-1);
  const shown = await canvasPixels(page);
  const row = height - 1 - y;
  const i = 3 * (row * width + x);
  assert.equal(last, `bytes: ${shown.rgb[i]} ${shown.rgb[i + 1]} ${shown.rgb[i + 2]}`);
  const cli = legacyRt(['trace', String(x), String(y), String(width), String(height)],
    { input: readFileSync(join(top, 'examples', name)) });
  assert.equal(cli.status, 0, cli.stderr);
  assert.equal(trace, cli.stdout.toString());
  console.log(`ok 5 - pixel (${x}, ${y}) of ${name}: the command line's trace, ending in "${last}"`);
  // The course's format too.
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  await page.check('input[name=format][value=course]');
  await page.waitForFunction((t) => document.getElementById('trace').textContent !== t, trace);
  const course = legacyRt(['trace', String(x), String(y), String(width), String(height),
    '--format', 'course'], { input: readFileSync(join(top, 'examples', name)) });
  assert.equal(await page.textContent('#trace'), course.stdout.toString());
  await page.check('input[name=format][value=readable]');
  await page.waitForFunction((t) => document.getElementById('trace').textContent === t, trace);
  console.log('ok 5 - and in the course\'s format');
}

// 6. A dropped image made with a known mistake: the command line's report, which names it
// (and, where `decision` is given, the decision flips the report says it takes).
async function namesTheMistake(page, name, variant, decision) {
  assert.equal(await openExample(page, name), 'done');
  const folder = scratch;
  const text = readFileSync(join(top, 'examples', name));
  writeFileSync(join(folder, name), text);
  const made = legacyRt(['320', '240', '--variant', variant, '-o', 'mine.ppm'],
    { input: text, cwd: folder });
  assert.equal(made.status, 0, made.stderr);
  const bytes = [...readFileSync(join(folder, 'mine.ppm'))];
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  const drop = await page.evaluateHandle((b) => {
    const transfer = new DataTransfer();
    transfer.items.add(new File([new Uint8Array(b)], 'mine.ppm'));
    return transfer;
  }, bytes);
  await page.dispatchEvent('#picture', 'drop', { dataTransfer: drop });
  assert.equal(await settled(page), 'done');
  const report = await page.textContent('#report');
  const cli = legacyRt(['compare', '--diagnose', name, 'mine.ppm'], { cwd: folder });
  assert.equal(cli.status, 1, cli.stderr);
  assert.equal(report, cli.stdout.toString());
  assert.match(report, new RegExp(`^  --variant ${variant}: `, 'm'));
  if (decision) assert.ok(report.includes(`\n  - ${decision}`), report);
  assert.equal(await page.getAttribute('#report', 'data-verdict'), 'differ');
  assert.equal(await page.isVisible('#diff'), true);
  console.log(`ok 6 - an image made with --variant ${variant} is diagnosed as it` +
    (decision ? `, with the decision "${decision}"` : ''));
}

// The browser gives a click whole CSS pixels: the position, relative to an element
// starting at `start`, of the first whole coordinate inside the image's pixel `offset`
// (for a canvas shown at one CSS pixel per pixel).
const inside = (start, offset) => Math.ceil(start + offset) - start + 0.05;

// 6b. A student's image of another size than the page's: the page switches to that size
// (saying so), so the diff lies on the pixels it is of, and a click on the report's
// worst pixel traces that pixel, whose bytes are the report's reference bytes.
async function comparesAtTheStudentsSize(page) {
  const name = 'spheres.txt';
  assert.equal(await openExample(page, name), 'done');
  await page.fill('#height', '300');
  assert.equal(await setAndRender(page, '#width', '320'), 'done');
  const folder = scratch;
  const text = readFileSync(join(top, 'examples', name));
  writeFileSync(join(folder, name), text);
  const made = legacyRt(['200', '150', '--variant', 'square-falloff', '-o', 'small.ppm'],
    { input: text, cwd: folder });
  assert.equal(made.status, 0, made.stderr);
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  await page.setInputFiles('#student', { name: 'small.ppm', mimeType: 'image/x-portable-pixmap',
    buffer: readFileSync(join(folder, 'small.ppm')) });
  assert.equal(await settled(page), 'done');
  await page.waitForFunction(() => window.legacyRt.state.comparison !== null);
  assert.deepEqual(await page.evaluate(() => [window.legacyRt.state.full.width, window.legacyRt.state.full.height]), [200, 150]);
  assert.deepEqual([await page.inputValue('#width'), await page.inputValue('#height')], ['200', '150']);
  assert.match(await page.textContent('#size-note'), /200x150/);
  const cli = legacyRt(['compare', '--diagnose', name, 'small.ppm'], { cwd: folder });
  assert.equal(await page.textContent('#report'), cli.stdout.toString());
  const json = JSON.parse(legacyRt(['compare', '--json', name, 'small.ppm'], { cwd: folder }).stdout);
  const worst = json.worst[0];
  const box = await page.locator('#image').boundingBox();
  assert.equal(Math.round(box.width), 200, 'the canvas is shown at its size');
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  await page.click('#image', { position: { x: inside(box.x, worst.x), y: inside(box.y, 150 - 1 - worst.y) } });
  assert.equal(await settled(page), 'done');
  assert.equal(await page.getAttribute('#trace-pane', 'data-pixel'), `${worst.x},${worst.y}`);
  assert.equal(await page.getAttribute('#trace-pane', 'data-bytes'), worst.reference.join(' '));
  console.log(`ok 6 - a 200x150 image compared on a 320x300 page: the page switches to 200x150, and the worst pixel (${worst.x}, ${worst.y}) traces to ${worst.reference.join(' ')}`);
}

// 3d. A scene that stops loading after a compare and a trace: the diff is hidden, the
// report and the trace are marked stale, and the error's docs/scene-format.md is a link
// to a file the page serves; once the scene loads again, nothing is marked.
async function marksStaleResults(page) {
  assert.equal(await page.isVisible('#diff'), true, 'a diff is shown');
  const good = await page.inputValue('#scene');
  const broken = readFileSync(join(top, 'tests/invalid/code_18_reflective_sphere.txt'), 'utf8');
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  await page.fill('#scene', broken);
  assert.equal(await settled(page), 'error');
  assert.equal(await page.isVisible('#diff'), false, 'no diff over the stale image');
  assert.equal(await page.isVisible('#diff-key'), false);
  for (const id of ['#report', '#trace']) {
    assert.ok(await page.getAttribute(id, 'data-stale'), `${id} is marked stale`);
  }
  const href = await page.getAttribute('#error-text a', 'href');
  assert.equal(href, 'docs/scene-format.md');
  const served = await page.evaluate(async (h) => (await fetch(h)).ok, href);
  assert.ok(served, 'the linked doc is served with the page');
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  await page.fill('#scene', good);
  assert.equal(await settled(page), 'done');
  for (const id of ['#report', '#trace']) {
    assert.equal(await page.getAttribute(id, 'data-stale'), null, `${id} is current again`);
  }
  assert.equal(await page.isVisible('#diff'), true, 'the diff is back');
  await page.click('#forget-student');
  assert.equal(await page.isVisible('#diff'), false);
  console.log('ok 3 - an error after a compare: the diff hidden, report and trace marked stale, the doc linked');
}

// 7. A student's own debug trace pasted beside a clicked pixel is read as
// `trace --against` reads it: the planted mistake of examples/studio-410-175.dbg is the
// first difference, the reference's own trace agrees, another pixel's is refused.
async function readsAStudentsTrace(page) {
  // Wide enough that the 640x480 canvas is shown at one CSS pixel per pixel: shown
  // smaller, some of its pixels are reached by no click.
  const viewport = page.viewportSize();
  await page.setViewportSize({ width: 2400, height: 1000 });
  assert.equal(await openExample(page, 'studio.txt'), 'done');
  await page.fill('#height', '480');
  assert.equal(await setAndRender(page, '#width', '640'), 'done');
  const box = await page.locator('#image').boundingBox();
  assert.equal(Math.round(box.width), 640, 'the canvas is shown at its size');
  const [x, y] = [410, 175];
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  await page.click('#image', { position: { x: inside(box.x, x), y: inside(box.y, 480 - 1 - y) } });
  assert.equal(await settled(page), 'done');
  assert.equal(await page.getAttribute('#trace-pane', 'data-pixel'), `${x},${y}`);
  const scene = readFileSync(join(top, 'examples/studio.txt'));
  const pixel = ['trace', String(x), String(y), '640', '480'];
  // Pasted: the page calls it dbg.txt, so the command line reads a dbg.txt too.
  const read = async (student) => {
    writeFileSync(join(scratch, 'dbg.txt'), student);
    await page.click('#against-box summary');
    await page.evaluate(() => { document.body.dataset.state = 'edited'; });
    await page.fill('#against', student);
    await page.waitForFunction(() => document.getElementById('against-report').dataset.agrees);
    assert.equal(await settled(page), 'done');
    const cli = legacyRt([...pixel, '--against', 'dbg.txt'], { input: scene, cwd: scratch });
    const shown = await page.textContent('#against-report');
    const agrees = await page.getAttribute('#against-report', 'data-agrees');
    await page.click('#forget-against');
    assert.equal(await page.isVisible('#against-report'), false);
    await page.click('#against-box summary');
    return { cli, shown, agrees };
  };
  const planted = await read(readFileSync(join(top, 'examples/studio-410-175.dbg'), 'utf8'));
  assert.equal(planted.cli.status, 1, planted.cli.stderr);
  assert.equal(planted.shown, planted.cli.stdout.toString());
  assert.equal(planted.agrees, 'no');
  assert.match(planted.shown, /^first difference: .*distance/);
  const own = legacyRt([...pixel, '--format', 'course'], { input: scene });
  const agreeing = await read(own.stdout.toString());
  assert.equal(agreeing.cli.status, 0, agreeing.cli.stderr);
  assert.equal(agreeing.shown, agreeing.cli.stdout.toString());
  assert.equal(agreeing.agrees, 'yes');
  const other = legacyRt(['trace', '100', '100', '640', '480', '--format', 'course'], { input: scene });
  const refused = await read(other.stdout.toString());
  assert.equal(refused.cli.status, 2);
  assert.equal(refused.shown, refused.cli.stderr.trimEnd());
  assert.equal(refused.agrees, 'unreadable');
  await page.setViewportSize(viewport);
  console.log(`ok 7 - a pasted trace of pixel (${x}, ${y}) is read as trace --against reads it: ${planted.shown.split('\n')[0].slice(0, 80)}…`);
}

// 7b. A whole image's trace (every pixel of an 8x6 render of studio.txt, one with the
// light's distance squared) gets `trace --against FILE 8 6`'s summary, and the group's
// pixel, clicked, is traced and read to its first difference.
async function readsAWholeTrace(page) {
  assert.equal(await openExample(page, 'studio.txt'), 'done');
  await page.fill('#height', '6');
  assert.equal(await setAndRender(page, '#width', '8'), 'done');
  const scene = readFileSync(join(top, 'examples/studio.txt'));
  let whole = '';
  for (let y = 0; y < 6; y++) {
    for (let x = 0; x < 8; x++) {
      const own = legacyRt(['trace', String(x), String(y), '8', '6', '--format', 'course'], { input: scene });
      let text = own.stdout.toString().replace(/^bytes:.*\n/m, '');
      // Pixel (5, 2): the first light's distance printed squared.
      if (x === 5 && y === 2) {
        text = text.replace(/distance to light is +([0-9.]+)/, (_, d) => `distance to light is ${(d * d).toFixed(3)}`);
      }
      whole += text;
    }
  }
  writeFileSync(join(scratch, 'dbg.txt'), whole);
  const cli = legacyRt(['trace', '--against', 'dbg.txt', '8', '6'], { input: scene, cwd: scratch });
  assert.equal(cli.status, 1, cli.stderr);
  await page.click('#against-box summary');
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  await page.fill('#against', whole);
  await page.waitForFunction(() => document.getElementById('against-summary').dataset.agrees);
  assert.equal(await settled(page), 'done');
  assert.equal(await page.textContent('#against-summary'), cli.stdout.toString());
  assert.equal(await page.getAttribute('#against-summary', 'data-agrees'), 'no');
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  await page.click('#against-summary .pixel-link');
  assert.equal(await settled(page), 'done');
  assert.equal(await page.getAttribute('#trace-pane', 'data-pixel'), '5,2');
  assert.match(await page.textContent('#against-report'), /^first difference: .*distance to the light/);
  await page.click('#forget-against');
  assert.equal(await page.isVisible('#against-summary'), false);
  console.log(`ok 7b - a whole trace is read as trace --against FILE 8 6 reads it: ${cli.stdout.toString().split('\n')[0]}`);
}

// 10. X and Y typed in are traced, whatever the canvas's shown size; the pixels of a
// compare report are links that trace them.
async function tracesTypedAndReportedPixels(page) {
  assert.equal(await openExample(page, 'spheres.txt'), 'done');
  await page.fill('#height', '480');
  assert.equal(await setAndRender(page, '#width', '640'), 'done');
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  await page.fill('#trace-x', '639');
  await page.fill('#trace-y', '0');
  await page.click('#trace-go');
  assert.equal(await settled(page), 'done');
  assert.equal(await page.getAttribute('#trace-pane', 'data-pixel'), '639,0');
  const scene = readFileSync(join(top, 'examples/spheres.txt'));
  const cli = legacyRt(['trace', '639', '0', '640', '480'], { input: scene });
  assert.equal(await page.textContent('#trace'), cli.stdout.toString());
  // A report's pixel: an image made with a mistake, compared, its first worst pixel clicked.
  const made = legacyRt(['640', '480', '--variant', 'square-falloff'], { input: scene });
  const file = join(scratch, 'square.ppm');
  writeFileSync(file, made.stdout);
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  await page.setInputFiles('#student', file);
  assert.equal(await settled(page), 'done');
  const link = page.locator('#report .pixel-link').first();
  const [, x, y] = (await link.textContent()).match(/\((\d+), (\d+)\)/);
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  await link.click();
  assert.equal(await settled(page), 'done');
  assert.equal(await page.getAttribute('#trace-pane', 'data-pixel'), `${x},${y}`);
  await page.click('#forget-student');
  console.log(`ok 10 - X and Y typed trace (639, 0); the report's pixel (${x}, ${y}) traces when clicked`);
}

// 11. Opened from disk, the page cannot start its module and worker: it says how to serve it.
async function saysToServeItFromDisk(browser) {
  const page = await browser.newPage();
  await page.goto(`file://${join(web, 'dist/index.html')}`);
  assert.equal(await page.isVisible('#served-note'), true);
  assert.match(await page.textContent('#served-note'), /web\/serve\.sh/);
  await page.close();
  console.log('ok 11 - opened from disk, the page says to serve it with web/serve.sh');
}

// 8. `legacy-rt grade`'s report, opened from disk as an instructor opens it: no console
// error, every image it names loads (the lazy ones made eager), nothing from the network.
async function gradeReportLoads(browser, file) {
  const folder = join(scratch, 'class');
  mkdirSync(join(folder, 'scenes'), { recursive: true });
  const made = (scene, student, argv, name) => {
    mkdirSync(join(folder, 'subs', student), { recursive: true });
    const out = legacyRt([...argv, '-o', join('subs', student, name)],
      { input: readFileSync(join(top, 'examples', `${scene}.txt`)), cwd: folder });
    assert.equal(out.status, 0, out.stderr);
  };
  for (const scene of ['spheres', 'studio']) {
    writeFileSync(join(folder, 'scenes', `${scene}.txt`), readFileSync(join(top, 'examples', `${scene}.txt`)));
    made(scene, 'ada', ['160', '120'], `${scene}.ppm`);
    made(scene, 'bo', ['160', '120', '--variant', 'no-shadows'], `${scene}.png`);
    made(scene, 'cy', ['160', '120', '--variant', 'square-falloff'], `${scene}.ppm`);
  }
  made('studio', 'di', ['120', '90'], 'studio.ppm');
  writeFileSync(join(folder, 'subs', 'di', 'spheres.ppm'), 'not an image');
  const graded = legacyRt(['grade', 'scenes', 'subs', '-o', 'report'], { cwd: folder });
  assert.equal(graded.status, 0, graded.stderr);
  const page = await browser.newPage({ viewport: { width: 1100, height: 900 } });
  const problems = [];
  page.on('pageerror', (error) => problems.push(error.message));
  page.on('console', (message) => message.type() === 'error' && problems.push(message.text()));
  const requests = [];
  page.on('request', (request) => requests.push(request.url()));
  await page.goto(`file://${join(folder, 'report', 'index.html')}`);
  const images = await page.evaluate(async () => {
    const all = [...document.images];
    for (const img of all) img.loading = 'eager';
    const loaded = await Promise.all(all.map((img) => img.decode().then(() => img.naturalWidth > 0, () => false)));
    return { count: all.length, broken: all.filter((_, i) => !loaded[i]).map((img) => img.getAttribute('src')) };
  });
  assert.deepEqual(images.broken, [], 'every image of the report loads');
  assert.ok(images.count >= 3 * 7, `${images.count} images`);
  assert.deepEqual(problems, [], 'no console error');
  assert.deepEqual(requests.filter((url) => !url.startsWith('file://')), [], 'nothing from the network');
  const cells = await page.$$eval('table.grades td.differ, table.grades td.match', (tds) => tds.length);
  assert.ok(cells >= 6, `${cells} graded cells`);
  if (file) {
    await page.screenshot({ path: file, clip: { x: 0, y: 0, width: 1100, height: 900 } });
    console.log(`screenshot: ${file}`);
  }
  await page.close();
  console.log(`ok 8 - grade's report opens from disk: ${images.count} images load, no console error`);
}

// 9. At a laptop's 1366x900 and a phone's 390x844, with a compare report and a traced
// pixel: no pane, trace or report wider than its box (nothing behind a sideways scroll),
// every control labelled; on the phone the image comes first, above the fold, and a
// tapped pixel's trace is scrolled into view.
async function fitsALaptopAndAPhone(browser, url, shots) {
  const name = 'quadrics_gallery.txt';
  const text = readFileSync(join(top, 'examples', name));
  const made = legacyRt(['320', '240', '--variant', 'no-shadows', '-o', 'layout.ppm'], { input: text, cwd: scratch });
  assert.equal(made.status, 0, made.stderr);
  for (const [width, height, shot] of [[1366, 900, shots.laptop], [390, 844, shots.phone]]) {
    const page = await browser.newPage({ viewport: { width, height } });
    await page.goto(url);
    assert.equal(await settled(page), 'done');
    if (width < 500) {
      const [image, editor] = await page.evaluate(() => ['image-pane', 'editor-pane']
        .map((id) => document.getElementById(id).getBoundingClientRect().top));
      assert.ok(image < editor, `the image (top ${image}) comes before the editor (${editor})`);
      const canvas = await page.locator('#image').boundingBox();
      assert.ok(canvas.y + canvas.height / 2 < height, `the image starts above the fold (top ${canvas.y})`);
    }
    assert.equal(await openExample(page, name), 'done');
    await page.evaluate(() => { document.body.dataset.state = 'edited'; });
    await page.setInputFiles('#student', { name: 'layout.ppm', mimeType: 'image/x-portable-pixmap',
      buffer: readFileSync(join(scratch, 'layout.ppm')) });
    assert.equal(await settled(page), 'done');
    await page.waitForFunction(() => window.legacyRt.state.comparison !== null);
    if (shot) {
      await page.evaluate(() => window.scrollTo(0, 0));
      await page.screenshot({ path: shot });
      console.log(`screenshot: ${shot}`);
    }
    const box = await page.locator('#image').boundingBox();
    await page.evaluate(() => { document.body.dataset.state = 'edited'; window.scrollTo(0, 0); });
    await page.locator('#image').scrollIntoViewIfNeeded();
    await page.click('#image', { position: { x: box.width * 0.5, y: box.height * 0.6 } });
    assert.equal(await settled(page), 'done');
    const trace = await page.evaluate(() => document.getElementById('trace-pane').getBoundingClientRect().top);
    assert.ok(trace >= -1 && trace < height - 40, `the trace is in view after the tap (top ${trace})`);
    const overflow = await page.evaluate(() => ['editor-pane', 'image-pane', 'trace-pane', 'trace', 'report', 'trace-command']
      .map((id) => document.getElementById(id))
      .filter((e) => e.scrollWidth > e.clientWidth + 1)
      .map((e) => `${e.id}: ${e.scrollWidth} > ${e.clientWidth}`));
    assert.deepEqual(overflow, [], `nothing wider than its box at ${width}x${height}`);
    const pageWidth = await page.evaluate(() => document.documentElement.scrollWidth);
    assert.ok(pageWidth <= width, `the page is ${pageWidth} wide at ${width}`);
    const unlabelled = await page.evaluate(() => [...document.querySelectorAll('input, select, textarea')]
      .filter((e) => e.labels.length === 0 && !e.getAttribute('aria-label'))
      .map((e) => e.id || e.name || e.type));
    assert.deepEqual(unlabelled, [], 'every control has a label');
    await page.close();
    console.log(`ok 9 - at ${width}x${height}: nothing cut at the right, every control labelled${width < 500 ? ', the image first and the trace scrolled to' : ''}`);
  }
}

// The page showing the gallery of quadrics with a traced pixel, for the docs: a fresh
// page, so that nothing of the tests shows.
async function takeScreenshot(browser, url, file) {
  const page = await browser.newPage({ viewport: { width: 1366, height: 900 } });
  await page.goto(url);
  assert.equal(await settled(page), 'done');
  assert.equal(await openExample(page, 'quadrics_gallery.txt'), 'done');
  await page.fill('#height', '300');
  assert.equal(await setAndRender(page, '#width', '400'), 'done');
  const box = await page.locator('#image').boundingBox();
  await page.evaluate(() => { document.body.dataset.state = 'edited'; });
  await page.click('#image', { position: { x: box.width * 0.5, y: box.height * 0.62 } });
  assert.equal(await settled(page), 'done');
  await page.screenshot({ path: file });
  await page.close();
  console.log(`screenshot: ${file}`);
}

// The page's render times against the native binary's, course scenes at 640x480.
async function benchmark(page) {
  const native = process.env.LEGACY_RT_RELEASE ?? join(top, 'target/release/legacy-rt');
  const folder = join(top, '../shared/course-scenes');
  const scenes = readdirSync(folder).filter((f) => f.endsWith('.txt')).sort();
  const median = (xs) => [...xs].sort((a, b) => a - b)[xs.length >> 1];
  const ratios = [];
  for (const scene of scenes) {
    const text = readFileSync(join(folder, scene), 'utf8');
    const browser = [];
    const cpu = [];
    for (let run = 0; run < 5; run++) {
      const ms = await page.evaluate(async (t) => {
        const r = await window.legacyRt.renderer.call('render',
          { text: t, width: 640, height: 480, choices: {} });
        return r.ms;
      }, text);
      browser.push(ms);
      const timed = spawnSync('bash', ['-c',
        'TIMEFORMAT="%3U %3S"; { time "$0" 640 480 --threads 1 < "$1" > /dev/null; } 2>&1',
        native, join(folder, scene)]);
      const [user, system] = timed.stdout.toString().trim().split(' ').map(Number);
      cpu.push((user + system) * 1000);
    }
    const ratio = median(browser) / median(cpu);
    ratios.push(ratio);
    console.log(`bench ${scene}: browser ${median(browser).toFixed(1)} ms, native ${median(cpu).toFixed(1)} ms CPU, ${ratio.toFixed(2)}x`);
  }
  const mean = Math.exp(ratios.reduce((s, r) => s + Math.log(r), 0) / ratios.length);
  console.log(`bench: the browser takes ${mean.toFixed(2)}x the native time (geometric mean over ${ratios.length} scenes)`);
  // How soon an example shows a picture once chosen (at 640 wide): the preview, or the
  // image itself.
  await page.fill('#height', '');
  await page.fill('#width', '640');
  const examples = readdirSync(join(top, 'examples')).filter((f) => f.endsWith('.txt')).sort();
  const first = [];
  for (const name of examples) {
    await openExample(page, name);
    const { firstPicture, full } = await page.evaluate(() => window.legacyRt.state);
    first.push(firstPicture);
    console.log(`bench ${name}: first picture after ${firstPicture.toFixed(0)} ms, the ${full.width}x${full.height} image after ${full.ms.toFixed(0)} ms of rendering`);
  }
  console.log(`bench: first picture of an example after at most ${Math.max(...first).toFixed(0)} ms (median ${median(first).toFixed(0)} ms)`);
}

// The sizes docs/web.md gives for web/dist/ (the folder and its WebAssembly), within a
// tenth of what was built.
function sizesAreTheDocs() {
  const sizeOf = (path) => {
    const stat = statSync(path);
    if (!stat.isDirectory()) return stat.size;
    return readdirSync(path).reduce((sum, name) => sum + sizeOf(join(path, name)), 0);
  };
  const docs = readFileSync(join(top, 'docs/web.md'), 'utf8').replace(/\s+/g, ' ');
  const [, folder, wasm] = docs.match(/about ([0-9.]+) MB, of which the WebAssembly is ([0-9.]+) MB/);
  const dist = join(web, 'dist');
  const built = { folder: sizeOf(dist) / 1e6, wasm: sizeOf(join(dist, 'pkg/legacy_rt_web_bg.wasm')) / 1e6 };
  for (const [what, said] of [['folder', folder], ['wasm', wasm]]) {
    assert.ok(Math.abs(built[what] - Number(said)) <= 0.1 * built[what],
      `docs/web.md says ${said} MB for the ${what}; it is ${built[what].toFixed(2)} MB`);
  }
  console.log(`ok 12 - docs/web.md's sizes are web/dist's: ${built.folder.toFixed(2)} MB, the WebAssembly ${built.wasm.toFixed(2)} MB`);
}

async function main() {
  assert.ok(existsSync(join(web, 'dist/index.html')), 'web/dist/ is built (web/build.sh)');
  sizesAreTheDocs();
  assert.ok(existsSync(binary), `${binary} is built`);
  const { server, url } = await serve();
  const browser = await chromium.launch({ executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium', args: FLAGS });
  try {
    const page = await browser.newPage({ viewport: { width: 1400, height: 820 } });
    const problems = [];
    page.on('pageerror', (error) => problems.push(error.message));
    await page.goto(url);
    assert.equal(await settled(page), 'done');
    if (bench) {
      await benchmark(page);
      return;
    }
    await rendersAsTheCommandLine(page, 'textured_planes.txt', 200, 150);
    await rendersAsTheCommandLine(page, 'quadrics_gallery.txt', 240, 180);
    await rendersTheAmbientStageAsTheCommandLine(page, 'tiled_planes.txt', 200, 150);
    await cancelsALongRender(page);
    await showsTheError(page);
    await namesTheSizeTyped(page);
    await namesAPastedScene(page);
    await takesAddedTextures(page);
    await tracesAClickedPixel(page, 'spheres.txt');
    await namesTheMistake(page, 'spheres.txt', 'square-falloff');
    await namesTheMistake(page, 'tube.txt', 'behind-root',
      'cylinder (line 11) does not block shadow rays whose base is inside it');
    await comparesAtTheStudentsSize(page);
    await marksStaleResults(page);
    await readsAStudentsTrace(page);
    await readsAWholeTrace(page);
    await tracesTypedAndReportedPixels(page);
    await saysToServeItFromDisk(browser);
    await gradeReportLoads(browser, gradeScreenshot);
    await fitsALaptopAndAPhone(browser, url, { laptop: null, phone: phoneScreenshot });
    if (screenshot) await takeScreenshot(browser, url, screenshot);
    assert.deepEqual(problems, [], 'no uncaught error on the page');
  } finally {
    await browser.close();
    server.kill();
    rmSync(scratch, { recursive: true, force: true });
  }
}

main().catch((error) => {
  console.error(error);
  process.exit(1);
});

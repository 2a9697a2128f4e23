// The page: the scene editor, the image, the trace panel and the comparison. All the
// work is the library's, in a Web Worker (worker.js); this file only wires the controls
// to it and draws what comes back.

const $ = (id) => document.getElementById(id);

// The page is running (served, not opened from disk): the note that says to serve it goes.
$('served-note').hidden = true;

// ---- The worker: requests as promises; a render in flight is cancelled by ending it.

class Renderer {
  constructor() {
    this.files = new Map(); // texture files, re-sent to a new worker
    this.workers = 0; // how many were started
    this.spawn();
  }

  spawn() {
    this.workers++;
    this.worker = new Worker('worker.js', { type: 'module' });
    this.pending = new Map();
    this.next = 0;
    this.worker.onmessage = ({ data }) => {
      const request = this.pending.get(data.id);
      this.pending.delete(data.id);
      if (!request) return;
      if ('error' in data) {
        if (data.error.fatal) this.restart(`the renderer stopped: ${data.error.message}`);
        request.reject(data.error);
      } else {
        request.resolve(data.result);
      }
    };
    this.worker.onerror = (event) => this.restart(`the renderer stopped: ${event.message}`);
    // The texture files again; cancelling this worker too only drops them with it.
    for (const [name, bytes] of this.files) {
      this.call('addFile', { name, bytes: bytes.slice() }).catch(() => {});
    }
  }

  call(op, args = {}) {
    const id = this.next++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { op, resolve, reject });
      this.worker.postMessage({ id, op, ...args });
    });
  }

  // Whether the worker is computing something that an edit makes stale.
  busy() {
    return [...this.pending.values()].some((request) => request.op !== 'addFile');
  }

  // Ends the worker and whatever it computes; its requests fail as cancelled.
  cancel() {
    this.worker.terminate();
    for (const request of this.pending.values()) request.reject({ cancelled: true });
    this.spawn();
  }

  // A new worker after the old one failed; its requests fail with `message`.
  restart(message) {
    this.worker.terminate();
    for (const request of this.pending.values()) request.reject({ message });
    this.spawn();
  }

  addFile(name, bytes) {
    this.files.set(name, bytes);
    return this.call('addFile', { name, bytes: bytes.slice() });
  }
}

const renderer = new Renderer();

// ---- State.

const state = {
  sceneName: 'scene.txt',
  openedText: null, // the text as the scene file was opened
  generation: 0, // bumped by every edit: answers to an older one are dropped
  full: null, // the last full-size render: { width, height, ms }
  picked: null, // the traced pixel: { x, row } in the full-size image
  againstName: 'dbg.txt', // the student's trace file, as the report names it
  student: null, // the compared image: { name, bytes }
  comparison: null,
  stale: false, // the scene no longer loads: what was computed from it is marked
  openedAt: null, // when the scene was opened, until its first picture is shown
  firstPicture: null, // how long that took, in ms
};

function setState(name) {
  document.body.dataset.state = name;
}

function choices() {
  const maxDist = Number($('max-dist').value);
  return {
    stage: $('stage').value,
    show: $('show').value || null,
    kernel: $('kernel').value,
    max_dist: Number.isFinite(maxDist) && $('max-dist').value !== '' ? maxDist : null,
    variants: $('variant-ids').value,
  };
}

function requestedSize() {
  const width = Math.trunc(Number($('width').value)) || 640;
  const height = Math.trunc(Number($('height').value)) || 0; // 0: from the world window
  return { width, height };
}

// ---- The editor: line numbers, and the error's line marked.

const editor = $('scene');

function lineCount() {
  let lines = 1;
  for (const c of editor.value) if (c === '\n') lines++;
  return lines;
}

function drawGutter() {
  const bad = Number($('error').dataset.line || 0);
  const numbers = [];
  for (let line = 1; line <= lineCount(); line++) {
    numbers.push(line === bad ? `<span class="bad">${line}</span>` : String(line));
  }
  $('gutter').innerHTML = numbers.join('\n') + '\n';
  placeLineMark();
}

function placeLineMark() {
  const bad = Number($('error').dataset.line || 0);
  const mark = $('line-mark');
  mark.hidden = !bad;
  if (!bad) return;
  const lineHeight = parseFloat(getComputedStyle(editor).lineHeight);
  const top = parseFloat(getComputedStyle(editor).paddingTop);
  mark.style.top = `${top + (bad - 1) * lineHeight - editor.scrollTop}px`;
}

editor.addEventListener('scroll', () => {
  $('gutter').scrollTop = editor.scrollTop;
  placeLineMark();
});

// The docs the library's messages name, as links to the copies the page is built with.
const DOC = /docs\/[a-z-]+\.md/g;

// Sets `element`'s text to `text`, with each docs/NAME.md it names a link.
function showWithLinks(element, text) {
  element.textContent = '';
  let at = 0;
  for (const match of text.matchAll(DOC)) {
    element.append(text.slice(at, match.index));
    const link = document.createElement('a');
    link.href = match[0];
    link.target = '_blank';
    link.textContent = match[0];
    element.append(link);
    at = match.index + match[0].length;
  }
  element.append(text.slice(at));
}

function showError(error) {
  const box = $('error');
  if (!error) {
    box.hidden = true;
    delete box.dataset.line;
  } else {
    box.hidden = false;
    showWithLinks($('error-text'), error.message);
    if (error.line) box.dataset.line = error.line;
    else delete box.dataset.line;
  }
  drawGutter();
}

// ---- Rendering, on every edit (debounced), a quarter-size preview first when slow.

const PREVIEW_ABOVE_MS = 150;

function draw(canvas, rgba, width, height) {
  canvas.width = width;
  canvas.height = height;
  canvas.getContext('2d').putImageData(new ImageData(new Uint8ClampedArray(rgba.buffer), width, height), 0, 0);
}

// The canvas shown at the full image's width, so that a preview is scaled up to it.
function displayWidth(width) {
  $('image').style.width = `${width}px`;
}

async function update() {
  const generation = ++state.generation;
  if (renderer.busy()) renderer.cancel();
  const text = editor.value;
  const { width, height } = requestedSize();
  const chosen = choices();
  setState('rendering');
  $('status').textContent = 'rendering…';
  const current = () => generation === state.generation;
  try {
    // A quarter-size preview (1/16 of the work) first for a scene just opened, whose
    // time is unknown, and after a slow render.
    if ((!state.full || state.full.ms > PREVIEW_ABOVE_MS) && width >= 64) {
      const w = Math.max(2, Math.round(width / 4));
      const h = height ? Math.max(2, Math.round(height / 4)) : 0;
      // A preview that fails is skipped: the full render's error names what was typed
      // (a width too large names that width, not the preview's quarter of it).
      const preview = await renderer
        .call('render', { text, width: w, height: h, choices: chosen })
        .catch((error) => {
          if (error.cancelled) throw error;
          return null;
        });
      if (!current()) return;
      if (preview) {
        showError(null);
        draw($('image'), preview.rgba, preview.width, preview.height);
        shown();
        displayWidth(width);
        $('image').classList.remove('stale');
        $('status').textContent = `preview at ${preview.width}x${preview.height}; rendering ${width} wide…`;
      }
    }
    const image = await renderer.call('render', { text, width, height, choices: chosen });
    if (!current()) return;
    showError(null);
    draw($('image'), image.rgba, image.width, image.height);
    shown();
    displayWidth(image.width);
    $('image').classList.remove('stale');
    markStale(false);
    state.full = { width: image.width, height: image.height, ms: image.ms };
    const { lights, objects } = image.scene;
    $('status').textContent =
      `${image.width}x${image.height}, ${objects} objects, ${lights} lights: ${image.ms.toFixed(0)} ms`;
    const picked = state.picked;
    if (picked && (picked.x >= image.width || picked.row >= image.height)) forgetPixel();
    if (state.picked) await tracePixel(state.picked.x, state.picked.row);
    else drawMark();
    if ($('against').value.trim()) await readAgainstAll();
    if (state.student) await compareStudent();
    if (current()) setState('done');
  } catch (error) {
    if (error.cancelled || !current()) return;
    $('image').classList.add('stale');
    markStale(true);
    if (error.scene) {
      showError(error);
      $('status').textContent = `the scene has an error on line ${error.line}`;
    } else {
      showError({ message: `error: ${error.message}` });
      $('status').textContent = 'nothing rendered';
    }
    setState('error');
  }
}

// What was computed from a scene that no longer loads (the diff, the report, the trace
// and the student's trace read against it) is marked stale, or unmarked once it loads.
function markStale(stale) {
  for (const id of ['report', 'trace', 'trace-command', 'against-report', 'against-summary']) {
    if (stale) $(id).dataset.stale = 'the scene no longer loads: this was computed from its last version';
    else delete $(id).dataset.stale;
  }
  state.stale = stale;
  showDiff();
}

// The diff and its key are shown when there is a comparison, it is asked for, and the
// scene still loads (over a greyed image it would be drawn at full strength).
function showDiff() {
  const shown = Boolean(state.comparison) && $('show-diff').checked && !state.stale;
  $('diff').hidden = !shown;
  $('diff-key').hidden = !shown;
}

// When the first picture of a scene just opened is on the canvas: how long it took.
function shown() {
  if (state.openedAt !== null) {
    state.firstPicture = performance.now() - state.openedAt;
    state.openedAt = null;
  }
}

let timer = null;
function soon() {
  clearTimeout(timer);
  timer = setTimeout(update, 200);
}

editor.addEventListener('input', () => {
  // Typed or pasted over: no longer the file opened, whose name the commands, the report
  // and the downloads would otherwise carry.
  if (editor.value !== state.openedText && state.sceneName !== YOUR_SCENE) {
    state.sceneName = YOUR_SCENE;
    $('example').value = '';
    $('scene-note').hidden = false;
  }
  drawGutter();
  soon();
});
for (const id of ['width', 'height', 'stage', 'show', 'kernel', 'max-dist']) {
  $(id).addEventListener('input', soon);
}

// ---- The trace of a clicked pixel, and the mark on it.

function forgetPixel() {
  state.picked = null;
  $('trace').textContent = '';
  $('trace-command').textContent = '';
  $('trace-title').textContent = 'Click a pixel to trace it';
  delete $('trace-pane').dataset.pixel;
  delete $('trace-pane').dataset.bytes;
  showAgainst(null);
}

function drawMark() {
  const mark = $('mark');
  const full = state.full;
  if (!full) return;
  mark.width = full.width;
  mark.height = full.height;
  const context = mark.getContext('2d');
  context.clearRect(0, 0, full.width, full.height);
  if (!state.picked || state.picked.x >= full.width || state.picked.row >= full.height) return;
  const { x, row } = state.picked;
  const reach = Math.max(6, Math.round(full.width / 40));
  context.fillStyle = 'rgba(0, 255, 0, 0.9)';
  context.fillRect(x - reach, row, reach - 2, 1);
  context.fillRect(x + 3, row, reach - 2, 1);
  context.fillRect(x, row - reach, 1, reach - 2);
  context.fillRect(x, row + 3, 1, reach - 2);
  context.strokeStyle = 'rgba(0, 255, 0, 0.9)';
  context.lineWidth = 1;
  context.strokeRect(x - 1.5, row - 1.5, 4, 4);
}

function traceFormat() {
  return document.querySelector('input[name=format]:checked').value;
}

async function tracePixel(x, row) {
  const full = state.full;
  if (!full) return;
  state.picked = { x, row };
  drawMark();
  const traced = await renderer.call('trace', {
    text: editor.value, x, row, width: full.width, height: full.height,
    choices: choices(), format: traceFormat(), sceneName: state.sceneName,
  });
  $('trace-title').textContent = `Pixel (${traced.x}, ${traced.y}) of ${full.width}x${full.height}`;
  $('trace-command').textContent = traced.command;
  $('trace').textContent = traced.text;
  $('trace-pane').dataset.pixel = `${traced.x},${traced.y}`;
  $('trace-pane').dataset.bytes = traced.bytes.join(' ');
  $('trace-x').value = String(traced.x);
  $('trace-y').value = String(traced.y);
  await readAgainst();
}

// Traces pixel (x, y), (0, 0) at the lower left, as typed or named by a report.
async function traceXY(x, y) {
  const full = state.full;
  if (!full) return;
  if (!(Number.isInteger(x) && Number.isInteger(y) && x >= 0 && y >= 0 && x < full.width && y < full.height)) {
    $('trace-title').textContent =
      `(${x}, ${y}) is outside the ${full.width}x${full.height} image: X below ${full.width}, Y below ${full.height}`;
    return;
  }
  setState('tracing');
  try {
    const row = await renderer.call('row', {
      text: editor.value, width: full.width, height: full.height, choices: choices(), y,
    });
    await tracePixel(x, row);
    setState('done');
  } catch (error) {
    if (error.cancelled) return;
    $('trace').textContent = error.message;
    setState('error');
  }
}

function tracedTyped() {
  traceXY(Number($('trace-x').value), Number($('trace-y').value));
}
$('trace-go').addEventListener('click', tracedTyped);
for (const id of ['trace-x', 'trace-y']) {
  $(id).addEventListener('keydown', (event) => {
    if (event.key === 'Enter') tracedTyped();
  });
}

// A report's text with each pixel it names at the start of a line, `(x, y)`, as a button
// that traces that pixel.
function showWithPixels(element, text) {
  element.textContent = '';
  for (const line of text.split(/(?<=\n)/)) {
    const match = line.match(/^(\s+(?:e\.g\. )?)\((\d+), (\d+)\)/);
    if (!match) {
      element.append(line);
      continue;
    }
    const [whole, lead, x, y] = match;
    element.append(lead);
    const button = document.createElement('button');
    button.className = 'pixel-link';
    button.textContent = `(${x}, ${y})`;
    button.title = `trace pixel (${x}, ${y})`;
    button.addEventListener('click', () => traceXY(Number(x), Number(y)));
    element.append(button, line.slice(whole.length));
  }
}

// ---- The student's own debug trace, read against the clicked pixel's (`--against`).

// The report's text and whether it agrees: 'yes', 'no', 'unreadable'; null hides it.
function showAgainst(text, agrees) {
  const report = $('against-report');
  report.hidden = text === null;
  report.textContent = text ?? '';
  if (agrees) report.dataset.agrees = agrees;
  else delete report.dataset.agrees;
}

// Reads the pasted or opened trace against the picked pixel of the full-size image.
async function readAgainst() {
  const student = $('against').value;
  const full = state.full;
  if (!state.picked || !full || !student.trim()) {
    showAgainst(null);
    return;
  }
  const { x, row } = state.picked;
  try {
    const read = await renderer.call('against', {
      text: editor.value, x, row, width: full.width, height: full.height,
      choices: choices(), fileName: state.againstName, student,
    });
    showAgainst(read.text, read.agrees ? 'yes' : 'no');
  } catch (error) {
    if (error.cancelled) throw error;
    showAgainst(`error: ${error.message}`, 'unreadable');
  }
}

// Reads every pixel of the pasted or opened trace, as `trace --against FILE W H` does:
// the counts, and each group's pixel as a button that traces it.
async function readAgainstAll() {
  const student = $('against').value;
  const full = state.full;
  const summary = $('against-summary');
  if (!full || !student.trim()) {
    summary.hidden = true;
    return;
  }
  summary.hidden = false;
  try {
    const read = await renderer.call('againstAll', {
      text: editor.value, width: full.width, height: full.height,
      choices: choices(), fileName: state.againstName, student,
    });
    showWithPixels(summary, read.text);
    summary.dataset.agrees = read.agrees ? 'yes' : 'no';
  } catch (error) {
    if (error.cancelled) throw error;
    summary.textContent = `error: ${error.message}`;
    summary.dataset.agrees = 'unreadable';
  }
}

// After the trace was pasted, typed, opened or dropped.
async function againstChanged() {
  $('against-box').open = true;
  setState('tracing');
  try {
    await readAgainstAll();
    if (state.picked) await readAgainst();
    setState('done');
  } catch (error) {
    if (!error.cancelled) setState('error');
  }
}

let againstTimer = null;
$('against').addEventListener('input', () => {
  state.againstName = 'dbg.txt';
  clearTimeout(againstTimer);
  againstTimer = setTimeout(againstChanged, 200);
});
async function takeAgainst(file) {
  $('against').value = await file.text();
  state.againstName = file.name;
  await againstChanged();
}
$('open-against').addEventListener('change', (event) => {
  const [file] = event.target.files;
  if (file) takeAgainst(file);
  event.target.value = '';
});
$('against').addEventListener('drop', (event) => {
  const [file] = event.dataTransfer.files;
  if (!file) return;
  event.preventDefault();
  takeAgainst(file);
});
$('forget-against').addEventListener('click', () => {
  $('against').value = '';
  showAgainst(null);
  $('against-summary').hidden = true;
  delete $('against-summary').dataset.agrees;
});

$('image').addEventListener('click', async (event) => {
  const canvas = $('image');
  const full = state.full;
  if (!full) return;
  const box = canvas.getBoundingClientRect();
  const x = Math.min(full.width - 1, Math.floor(((event.clientX - box.left) / box.width) * full.width));
  const row = Math.min(full.height - 1, Math.floor(((event.clientY - box.top) / box.height) * full.height));
  setState('tracing');
  try {
    await tracePixel(x, row);
    // On a narrow screen the trace is below the image: show it.
    const pane = $('trace-pane').getBoundingClientRect();
    if (pane.top > window.innerHeight - 40 || pane.bottom < 0) {
      $('trace-pane').scrollIntoView({ block: 'start' });
    }
    setState('done');
  } catch (error) {
    if (error.cancelled) return;
    $('trace').textContent = error.message;
    setState('error');
  }
});

for (const radio of document.querySelectorAll('input[name=format]')) {
  radio.addEventListener('change', () => state.picked && tracePixel(state.picked.x, state.picked.row));
}

// ---- Comparing a student's image: the report, the diff over the canvas, the diagnosis.

async function compareStudent() {
  const { name, bytes } = state.student;
  $('report').hidden = false;
  $('report').textContent = `comparing ${name}${$('diagnose').checked ? ' and diagnosing' : ''}…`;
  try {
    const result = await renderer.call('compare', {
      text: editor.value, sceneName: state.sceneName, name, bytes: bytes.slice(),
      choices: choices(),
      levels: Math.trunc(Number($('tolerance').value)) || 0,
      allow: Number($('allow').value) || 0,
      diagnose: $('diagnose').checked,
    });
    const full = state.full;
    if (full && (result.width !== full.width || result.height !== full.height)) {
      // The report is of the student image's size: the page renders at that size too,
      // so that the diff lies on the pixels it is of and a click traces what it shows.
      $('width').value = String(result.width);
      $('height').value = String(result.height);
      $('size-note').textContent = `W and H set to ${result.width}x${result.height}, the size of ${name}: ` +
        'the reference is compared at the size of the student\'s image.';
      $('size-note').hidden = false;
      state.comparison = null;
      showDiff();
      await update();
      return;
    }
    state.comparison = result;
    showWithPixels($('report'), result.text);
    $('report').dataset.verdict = result.matches ? 'match' : 'differ';
    draw($('diff'), result.diff, result.width, result.height);
    showDiff();
  } catch (error) {
    if (error.cancelled) throw error;
    state.comparison = null;
    $('report').textContent = error.scene ? 'the scene has an error' : error.message;
    $('report').dataset.verdict = 'error';
    showDiff();
  }
}

async function takeStudent(file) {
  state.student = { name: file.name, bytes: new Uint8Array(await file.arrayBuffer()) };
  $('forget-student').hidden = false;
  setState('comparing');
  try {
    await compareStudent();
    setState('done');
  } catch (error) {
    if (!error.cancelled) setState('error');
  }
}

$('student').addEventListener('change', (event) => {
  const [file] = event.target.files;
  if (file) takeStudent(file);
  event.target.value = '';
});
$('show-diff').addEventListener('change', showDiff);
for (const id of ['tolerance', 'allow', 'diagnose']) {
  $(id).addEventListener('change', () => state.student && takeStudent(new File([state.student.bytes], state.student.name)));
}

const picture = $('picture');
picture.addEventListener('dragover', (event) => {
  event.preventDefault();
  picture.classList.add('dragging');
});
picture.addEventListener('dragleave', () => picture.classList.remove('dragging'));
picture.addEventListener('drop', (event) => {
  event.preventDefault();
  picture.classList.remove('dragging');
  const [file] = event.dataTransfer.files;
  if (file) takeStudent(file);
});

// A scene file dropped on the editor replaces the text.
editor.addEventListener('drop', async (event) => {
  const [file] = event.dataTransfer.files;
  if (!file) return;
  event.preventDefault();
  openScene(file.name, await file.text());
});

// ---- Scenes, examples and textures.

// The name the commands give a scene typed or pasted into the editor.
const YOUR_SCENE = 'scene.txt';

function openScene(name, text) {
  state.sceneName = name;
  state.openedText = text;
  $('scene-note').hidden = true;
  forgetPixel();
  state.full = null;
  state.openedAt = performance.now();
  editor.value = text;
  editor.scrollTop = 0;
  drawGutter();
  update();
}

$('open-scene').addEventListener('change', async (event) => {
  const [file] = event.target.files;
  if (file) {
    $('example').value = '';
    openScene(file.name, await file.text());
  }
  event.target.value = '';
});

async function addTextures(files) {
  let names = [];
  for (const file of files) {
    names = await renderer.addFile(file.name, new Uint8Array(await file.arrayBuffer()));
  }
  $('textures').hidden = names.length === 0;
  $('textures').textContent = `Texture files: ${names.join(', ')}`;
}

$('add-textures').addEventListener('change', async (event) => {
  await addTextures([...event.target.files]);
  event.target.value = '';
  update();
});

async function loadExamples() {
  const index = await (await fetch('examples/index.json')).json();
  for (const name of index.scenes) {
    const option = document.createElement('option');
    option.value = name;
    option.textContent = name;
    $('example').append(option);
  }
  // The examples' textures, under the names the examples give them.
  for (const name of index.textures) {
    const bytes = new Uint8Array(await (await fetch(`examples/textures/${name}`)).arrayBuffer());
    await renderer.addFile(`examples/textures/${name}`, bytes);
  }
  return index;
}

async function openExample(name) {
  const text = await (await fetch(`examples/${name}`)).text();
  openScene(name, text);
}

$('example').addEventListener('change', () => {
  const name = $('example').value;
  if (name) openExample(name);
});

// ---- Downloads.

async function download(format) {
  const bytes = await renderer.call(format);
  const type = format === 'png' ? 'image/png' : 'image/x-portable-pixmap';
  const link = document.createElement('a');
  link.href = URL.createObjectURL(new Blob([bytes], { type }));
  link.download = state.sceneName.replace(/\.[^.]*$/, '') + `.${format}`;
  link.click();
  setTimeout(() => URL.revokeObjectURL(link.href), 10_000);
}

$('download-png').addEventListener('click', () => download('png'));
$('download-ppm').addEventListener('click', () => download('ppm'));

// ---- The controls' vocabulary, from the library.

function fill(select, names, chosen) {
  for (const name of names) {
    const option = document.createElement('option');
    option.value = option.textContent = name;
    option.selected = name === chosen;
    select.append(option);
  }
}

function variantControls(variants) {
  const input = document.createElement('input');
  input.id = 'variant-ids';
  input.setAttribute('aria-label', 'Variant ids (--variant)');
  input.placeholder = 'ids, comma-separated, e.g. no-shadows,max-dist=40';
  input.style.width = '100%';
  const box = $('variants');
  box.before(input);
  const checks = [];
  for (const { id, about } of variants) {
    const label = document.createElement('label');
    const check = document.createElement('input');
    check.type = 'checkbox';
    check.value = id;
    label.title = about;
    label.append(check, ` ${id}`);
    box.append(label);
    checks.push(check);
    check.addEventListener('change', () => {
      const ids = checks.filter((c) => c.checked).map((c) => c.value);
      input.value = ids.join(',');
      input.dispatchEvent(new Event('input'));
    });
  }
  input.addEventListener('input', () => {
    $('variant-list').textContent = input.value || 'none';
    soon();
  });
}

async function start() {
  const vocabulary = await renderer.call('vocabulary');
  fill($('stage'), vocabulary.stages, 'full');
  fill($('show'), vocabulary.shows, null);
  fill($('kernel'), vocabulary.kernels, 'accurate');
  variantControls(vocabulary.variants);
  const index = await loadExamples();
  const first = index.scenes.includes('spheres.txt') ? 'spheres.txt' : index.scenes[0];
  $('example').value = first;
  await openExample(first);
}

// Drops the compared image: its report and diff go.
function forgetStudent() {
  state.student = null;
  state.comparison = null;
  $('report').hidden = true;
  showDiff();
  $('size-note').hidden = true;
  $('forget-student').hidden = true;
}

$('forget-student').addEventListener('click', forgetStudent);

// For the browser test and the speed measurement: the page's worker, to call directly.
window.legacyRt = { renderer, state, update, openScene, takeStudent };

start();

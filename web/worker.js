// The page's renderer, off the main thread: it holds the WebAssembly `Session` (the
// scene, the texture files, the last image) and answers the page's requests one at a
// time. The page cancels a long render by ending this worker and starting another.
//
// A request is { id, op, text, ...arguments }; the answer is { id, result } or
// { id, error }. Every op that takes `text` loads it first when it is not the loaded one.

import init, { Session, vocabulary } from './pkg/legacy_rt_web.js';

let session = null;
const ready = init().then(() => {
  session = new Session();
});
let loadedText = null;
let loaded = null;

// Loads `text` unless it is loaded; the load's result ({ ok } or { error }).
function load(text) {
  if (text !== loadedText) {
    loaded = JSON.parse(session.load(text));
    loadedText = text;
  }
  return loaded;
}

// A load error as an answer's error: the command line's message and where.
function sceneError(result) {
  return { scene: true, ...result.error };
}

const ops = {
  vocabulary: () => JSON.parse(vocabulary()),

  addFile({ name, bytes }) {
    session.add_file(name, bytes);
    loadedText = null; // a texture may change what the scene loads to
    return JSON.parse(session.file_names());
  },

  load: ({ text }) => load(text),

  render({ text, width, height, choices }) {
    const result = load(text);
    if (result.error) throw sceneError(result);
    const start = performance.now();
    const rgba = session.render(width, height, JSON.stringify(choices));
    const ms = performance.now() - start;
    const w = width;
    const h = rgba.length / 4 / w;
    return { rgba, width: w, height: h, ms, scene: result.ok };
  },

  trace({ text, x, row, width, height, choices, format, sceneName }) {
    const result = load(text);
    if (result.error) throw sceneError(result);
    const json = session.trace(x, row, width, height, JSON.stringify(choices), format, sceneName);
    return JSON.parse(json);
  },

  against({ text, x, row, width, height, choices, fileName, student }) {
    const result = load(text);
    if (result.error) throw sceneError(result);
    const json = session.against(x, row, width, height, JSON.stringify(choices), fileName, student);
    return JSON.parse(json);
  },

  againstAll({ text, width, height, choices, fileName, student }) {
    const result = load(text);
    if (result.error) throw sceneError(result);
    const json = session.against_all(width, height, JSON.stringify(choices), fileName, student);
    return JSON.parse(json);
  },

  row({ text, width, height, choices, y }) {
    const result = load(text);
    if (result.error) throw sceneError(result);
    return session.row(width, height, JSON.stringify(choices), y);
  },

  compare({ text, sceneName, name, bytes, choices, levels, allow, diagnose }) {
    const result = load(text);
    if (result.error) throw sceneError(result);
    const comparison = session.compare(
      sceneName, name, bytes, JSON.stringify(choices), levels, allow, diagnose);
    const answer = {
      text: comparison.text(),
      report: JSON.parse(comparison.json()),
      matches: comparison.matches(),
      diff: comparison.diff(),
      width: comparison.width(),
      height: comparison.height(),
    };
    comparison.free();
    return answer;
  },

  png: () => session.png(),
  ppm: () => session.ppm(),
};

self.onmessage = async (event) => {
  const { id, op, ...args } = event.data;
  await ready;
  try {
    const result = ops[op](args);
    const transfer = [result?.rgba?.buffer, result?.diff?.buffer, result?.buffer]
      .filter((buffer) => buffer instanceof ArrayBuffer);
    self.postMessage({ id, result }, transfer);
  } catch (error) {
    // A trap (out of memory, a bug) leaves the WebAssembly instance unusable: the page
    // starts another worker.
    const fatal = error instanceof WebAssembly.RuntimeError;
    const plain = error instanceof Error ? { message: error.message, fatal } : error;
    self.postMessage({ id, error: plain });
  }
};

// Drives particle-demo's web page (build-web/particle-demo.html) in headless
// Chromium as the desktop's GUI tests drive the program: options in the URL's
// query, a script of input events (demos/gui/SCRIPTING.md) through
// window.particleDemo.script, and the state log (--log-state) read back
// through window.particleDemo.stateLog(). The page is served from 127.0.0.1
// by a static server of this process.
'use strict';
const fs = require('node:fs');
const http = require('node:http');
const path = require('node:path');
const { execFileSync } = require('node:child_process');
const puppeteer = require('puppeteer-core');

const pageDir = process.env.PARTICLES_WEB_PAGE;  // build-web/
const chromium = process.env.PARTICLES_CHROMIUM || '/usr/bin/chromium';

const contentTypes = { '.html': 'text/html', '.js': 'text/javascript', '.wasm': 'application/wasm' };

// Serves pageDir on 127.0.0.1 at a free port.
function serve() {
  const server = http.createServer((request, response) => {
    const name = path.normalize(decodeURIComponent(new URL(request.url, 'http://x').pathname)).replace(/^\/+/, '');
    const file = path.join(pageDir, name || 'index.html');
    if (!file.startsWith(path.resolve(pageDir)) || !fs.existsSync(file) || !fs.statSync(file).isFile()) {
      response.writeHead(404);
      response.end();
      return;
    }
    response.writeHead(200, { 'Content-Type': contentTypes[path.extname(file)] || 'application/octet-stream' });
    fs.createReadStream(file).pipe(response);
  });
  return new Promise(resolve => server.listen(0, '127.0.0.1', () => resolve(server)));
}

// Chromium without a GPU: WebGL 2 through SwiftShader (a software rasteriser,
// as llvmpipe is under Xvfb for the desktop). Root needs --no-sandbox.
async function launch() {
  return puppeteer.launch({
    executablePath: chromium,
    headless: true,
    args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--no-sandbox', '--disable-dev-shm-usage'],
  });
}

// One browser and one server for a test file.
class PageSession {
  async start() {
    if (!pageDir || !fs.existsSync(path.join(pageDir, 'particle-demo.html')))
      throw new Error(`PARTICLES_WEB_PAGE=${pageDir}: no particle-demo.html there (bash scripts/build-web.sh builds it)`);
    this.server = await serve();
    this.browser = await launch();
    this.base = `http://127.0.0.1:${this.server.address().port}/particle-demo.html`;
  }
  async stop() {
    if (this.browser) await this.browser.close();
    if (this.server) this.server.close();
  }

  // Opens the page with `query` (e.g. "scene=cloth&frames=60") and `script`
  // (the text of a --script file, or null). The window is the desktop's
  // default 1180x760 unless the query sets it.
  async open(query, script = null) {
    const page = await this.browser.newPage();
    await page.setViewport({ width: 1400, height: 1000, deviceScaleFactor: 1 });
    await page.evaluateOnNewDocument(text => {
      window.particleDemo = { script: text };
    }, script);
    await page.goto(`${this.base}?${query}`);
    await page.waitForFunction(() => window.particleDemo && (window.particleDemo.frames > 0 || window.particleDemo.exitCode !== null),
                               { timeout: 60000 });
    return page;
  }

  // Opens the page and waits for the demo to end (the query's frames=N, or q
  // in the script); returns its exit code, state log and printed output.
  async run(query, script = null, timeoutMs = 120000) {
    const page = await this.open(query, script);
    await page.waitForFunction(() => window.particleDemo.exitCode !== null, { timeout: timeoutMs, polling: 50 });
    const result = await page.evaluate(() => ({
      exitCode: window.particleDemo.exitCode,
      output: window.particleDemo.output,
      log: window.particleDemo.frames > 0 ? window.particleDemo.stateLog() : '',
    }));
    result.page = page;
    result.state = parseStateLog(result.log);
    return result;
  }
}

// Waits until the page has drawn `count` more frames.
async function waitFrames(page, count) {
  const start = await page.evaluate(() => window.particleDemo.frames);
  await page.waitForFunction(target => window.particleDemo.frames >= target, { timeout: 60000, polling: 20 }, start + count);
}

async function stateOf(page) {
  return parseStateLog(await page.evaluate(() => window.particleDemo.stateLog()));
}

// The records of a state log (demos/gui/state_log.h) the tests read.
function parseStateLog(text) {
  const state = { frames: 0, panes: [] };
  const pane = k => {
    while (state.panes.length <= k) state.panes.push({ particles: [] });
    return state.panes[k];
  };
  for (const line of text.split('\n')) {
    const f = line.split(',');
    switch (f[0]) {
      case 'frame': state.frames = Number(f[1]); break;
      case 'paused': state.paused = f[1] === '1'; break;
      case 'pane': Object.assign(pane(Number(f[1])), {
        scene: f[2], integrator: f[3], dt: Number(f[4]), time: Number(f[5]), steps: Number(f[6]),
        diverged: f[7] === '1', mouseSprings: Number(f[8]), energy: Number(f[9]) });
        break;
      case 'view': pane(Number(f[1])).view = {
        x: Number(f[2]), y: Number(f[3]), width: Number(f[4]), height: Number(f[5]),
        min: [Number(f[6]), Number(f[7])], max: [Number(f[8]), Number(f[9])] };
        break;
      case 'particle': pane(Number(f[1])).particles[Number(f[2])] = {
        x: [Number(f[3]), Number(f[4])], v: [Number(f[5]), Number(f[6])], mass: Number(f[7]), pinned: f[8] === '1' };
        break;
      case 'wall': (pane(Number(f[1])).walls = pane(Number(f[1])).walls || []).push({
        min: [Number(f[2]), Number(f[3])], max: [Number(f[4]), Number(f[5])] });
        break;
      case 'grab': pane(Number(f[1])).grab = { particle: Number(f[2]), target: [Number(f[3]), Number(f[4])] }; break;
      case 'real-time': state.realTime = { lastSecond: Number(f[1]), simSeconds: Number(f[2]), wallSeconds: Number(f[3]) }; break;
      case 'overlay': (state.overlays = state.overlays || []).push({ kind: f[1], x: Number(f[2]), y: Number(f[3]),
                                                                      width: Number(f[4]), height: Number(f[5]) });
        break;
      default: break;
    }
  }
  return state;
}

// A world point's pixel in the pane (demos/gui/view.h ViewTransform::toPixel).
function toPixel(view, p) {
  const scale = view.width / (view.max[0] - view.min[0]);
  return [view.x + (p[0] - view.min[0]) * scale, view.y + (view.max[1] - p[1]) * scale];
}

// The page's pixels as the browser shows them: a PNG screenshot decoded by
// the browser itself (an image drawn on a 2D canvas), rows top to bottom.
// canvasOnly: the demo's canvas alone (SCRIPTING.md's picture of the page), else the page.
async function screenshot(page, file = null, canvasOnly = false) {
  const clip = canvasOnly ? await (await page.$('#canvas')).boundingBox() : undefined;
  const png = await page.screenshot({ type: 'png', omitBackground: false, clip });
  if (file) fs.writeFileSync(file, png);
  const pixels = await page.evaluate(async base64 => {
    const image = new Image();
    image.src = 'data:image/png;base64,' + base64;
    await image.decode();
    const canvas = document.createElement('canvas');
    canvas.width = image.width;
    canvas.height = image.height;
    const context = canvas.getContext('2d');
    context.drawImage(image, 0, 0);
    return { width: image.width, height: image.height,
             rgba: Array.from(context.getImageData(0, 0, image.width, image.height).data) };
  }, Buffer.from(png).toString('base64'));
  pixels.at = (x, y) => {
    const k = 4 * (Math.round(y) * pixels.width + Math.round(x));
    return [pixels.rgba[k], pixels.rgba[k + 1], pixels.rgba[k + 2]];
  };
  return pixels;
}

// A colour of demos/gui/palette.h by its name there, so that the tests and the
// demo share one definition.
function paletteColour(name) {
  const text = fs.readFileSync(path.join(__dirname, '../../demos/gui/palette.h'), 'utf8');
  const match = text.match(new RegExp(`constexpr Rgb ${name}\\{(\\d+), (\\d+), (\\d+)\\}`));
  if (!match) throw new Error(`palette.h has no colour ${name}`);
  return [Number(match[1]), Number(match[2]), Number(match[3])];
}

// The native programs, for the same run on the desktop.
function runNative(program, args, cwd) {
  return execFileSync(program, args, { cwd, encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
}

module.exports = { PageSession, waitFrames, stateOf, parseStateLog, toPixel, screenshot, paletteColour, runNative };

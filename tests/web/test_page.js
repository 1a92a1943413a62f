// particle-demo's web page in headless Chromium, held against the desktop:
// the native particle-demo (under Xvfb, as the GUI tests run it) and the
// headless runner particle-lab, given the same options and script.
// Run by ctest (label web): node --test --test-name-pattern NAME test_page.js
'use strict';
const assert = require('node:assert/strict');
const fs = require('node:fs');
const os = require('node:os');
const path = require('node:path');
const { test, before, after } = require('node:test');
const { PageSession, waitFrames, stateOf, parseStateLog, toPixel, screenshot, paletteColour, runNative } =
    require('./page_driver.js');

const demo = process.env.PARTICLE_DEMO;  // the native programs
const lab = process.env.PARTICLE_LAB;
const output = process.env.PARTICLES_WEB_TEST_OUTPUT || fs.mkdtempSync(path.join(os.tmpdir(), 'web-tests-'));
fs.mkdirSync(output, { recursive: true });

const session = new PageSession();
// ctest runs one test a process (PARTICLES_WEB_TEST, --test-name-pattern):
// a name that matches none must fail, not pass having run nothing.
let ran = 0;
const webTest = (name, body) => test(name, async () => { ++ran; await body(); });
before(() => session.start());
after(async () => {
  await session.stop();
  if (process.env.PARTICLES_WEB_TEST) assert.equal(ran, 1, `no test ran for ${process.env.PARTICLES_WEB_TEST}`);
});

// The native demo's state log for the same options and script.
function nativeState(name, args, script = null) {
  const dir = path.join(output, name);
  fs.mkdirSync(dir, { recursive: true });
  const extra = [];
  if (script !== null) {
    fs.writeFileSync(path.join(dir, 'script.txt'), script);
    extra.push('--script', 'script.txt');
  }
  runNative(demo, [...args, ...extra, '--log-state', 'state.txt'], dir);
  return parseStateLog(fs.readFileSync(path.join(dir, 'state.txt'), 'utf8'));
}

const distance = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1]);
const near = (c, expected, tolerance) => c.every((v, k) => Math.abs(v - expected[k]) <= tolerance);

// Every number key, pressed on the page's keyboard, loads the scene the
// desktop loads for it (--key): its label, integrator, dt and particles.
webTest('EveryNumberKeyLoadsItsScene', async () => {
  const page = await session.open('paused&no-panel');
  for (const key of ['1', '2', '3', '4', '5', '6', '7', '8', '9', '0']) {
    const expected = nativeState(`key-${key}`, ['--key', key, '--paused', '--frames', '1', '--no-panel']).panes[0];
    await page.keyboard.press(key);
    await waitFrames(page, 3);
    const pane = (await stateOf(page)).panes[0];
    assert.equal(pane.scene, expected.scene, `key ${key}`);
    assert.equal(pane.integrator, expected.integrator, `key ${key}`);
    assert.equal(pane.dt, expected.dt, `key ${key}`);
    assert.equal(pane.particles.length, expected.particles.length, `key ${key}`);
    pane.particles.forEach((p, i) => assert.equal(p.mass, expected.particles[i].mass, `key ${key}, particle ${i}`));
  }
  await page.close();
});

// As DemoMouse.DragPullsTheClothParticleTowardTheCursorAndReleaseRemovesTheSpring:
// the cloth's corner, dragged 0.3 right and down, follows the cursor; let go,
// the mouse spring is gone.
webTest('DragMovesTheGrabbedParticleTowardTheCursor', async () => {
  // No stepping budget: every frame steps its whole simulated time, on a
  // loaded machine too, so that the page's run and the desktop's are one run.
  const scene = 'scene=cloth&preset=seed&param=links=4&step-budget=1000000';
  const start = (await session.run(`${scene}&frames=1&paused`)).state.panes[0];
  let corner = 0;
  start.particles.forEach((p, i) => {
    const c = start.particles[corner];
    if (p.x[0] - p.x[1] > c.x[0] - c.x[1]) corner = i;
  });
  const from = start.particles[corner].x, to = [from[0] + 0.3, from[1] - 0.3];
  let held = `5 down world ${from[0]} ${from[1]}\n`;
  for (let k = 1; k <= 30; ++k)
    held += `${5 + k} move world ${from[0] + (to[0] - from[0]) * k / 30} ${from[1] + (to[1] - from[1]) * k / 30}\n`;
  const dragging = (await session.run(`${scene}&frames=150`, held)).state.panes[0];
  const alone = (await session.run(`${scene}&frames=150`)).state.panes[0];
  const after = (await session.run(`${scene}&frames=160`, held + `150 up world ${to[0]} ${to[1]}\n`)).state.panes[0];
  assert.equal(dragging.mouseSprings, 1);
  assert.ok(distance(dragging.particles[corner].x, to) < 0.5 * distance(from, to));
  assert.ok(distance(dragging.particles[corner].x, to) < distance(alone.particles[corner].x, to) - 0.1);
  assert.equal(after.mouseSprings, 0);
  // The desktop, given the same script, holds the particle where the page does.
  const native = nativeState('drag', ['--scene', 'cloth', '--preset', 'seed', '--param', 'links=4', '--step-budget', '1000000',
                                      '--frames', '150'], held);
  assert.ok(distance(native.panes[0].particles[corner].x, dragging.particles[corner].x) < 1e-9);
});

// i moves every pane to the next integrator of the table, keeping the state,
// as on the desktop (one step a frame: the same steps on any machine).
webTest('IntegratorKeyChangesTheIntegrator', async () => {
  const script = '5 key i\n';
  const page = (await session.run('scene=test-chain&frames=10&no-panel&lockstep', script)).state.panes[0];
  const scene = (await session.run('scene=test-chain&frames=10&no-panel&lockstep')).state.panes[0];
  const native = nativeState('integrator', ['--scene', 'test-chain', '--frames', '10', '--no-panel', '--lockstep'], script).panes[0];
  assert.notEqual(page.integrator, scene.integrator);
  assert.equal(page.integrator, native.integrator);
  assert.equal(page.steps, native.steps);
  for (let i = 0; i < page.particles.length; ++i)
    assert.ok(distance(page.particles[i].x, native.particles[i].x) < 1e-9, `particle ${i}`);
});

// As DemoScreenshot.ParticlesWhereTheLogSays…: on the page's screenshot each
// particle's pixel has the particle's colour where the logged state and view
// put it, and pixels far from every particle are the background. The shot
// with the panel is SCRIPTING.md's picture of the page.
webTest('ScreenshotParticlesWhereTheLogSays', async () => {
  const run = await session.run('scene=cloth&param=links=8&frames=90&no-panel&window=900x700', '0 key c\n');
  assert.equal(run.exitCode, 0, run.output);
  const image = await screenshot(run.page, path.join(output, 'page-cloth.png'));
  const pane = run.state.panes[0];
  const particle = paletteColour('particle'), pinned = paletteColour('pinnedParticle');
  const background = paletteColour('background');
  let checked = 0, drawn = 0;
  for (const q of pane.particles) {
    const [x, y] = toPixel(pane.view, q.x);
    if (x < pane.view.x + 2 || y < pane.view.y + 2 || x > pane.view.x + pane.view.width - 3 ||
        y > pane.view.y + pane.view.height - 3)
      continue;
    if (run.state.overlays.some(o => x >= o.x - 4 && x < o.x + o.width + 4 && y >= o.y - 4 && y < o.y + o.height + 4))
      continue;
    ++checked;
    let found = false;
    for (let dy = -1; dy <= 1 && !found; ++dy)
      for (let dx = -1; dx <= 1 && !found; ++dx) found = near(image.at(Math.floor(x) + dx, Math.floor(y) + dy), q.pinned ? pinned : particle, 12);
    drawn += found;
  }
  assert.ok(checked >= 50, `${checked} particles checked`);
  assert.equal(drawn, checked);
  // Pixels 40 px below the lowest particle, across the pane and outside
  // every wall, are the background.
  const lowest = Math.max(...pane.particles.map(q => toPixel(pane.view, q.x)[1]));
  const inWall = (x, y) => (pane.walls || []).some(w => {
    const [x0, y1] = toPixel(pane.view, w.min), [x1, y0] = toPixel(pane.view, w.max);
    return x >= x0 - 4 && x <= x1 + 4 && y >= y0 - 4 && y <= y1 + 4;
  });
  let empty = 0;
  const y = lowest + 40;
  for (let x = pane.view.x + 20; x < pane.view.x + pane.view.width - 20 && y < pane.view.y + pane.view.height - 20; x += 15) {
    if (inWall(x, y)) continue;
    assert.ok(near(image.at(x, y), background, 0), `at ${x},${y}: ${image.at(x, y)}`);
    ++empty;
  }
  assert.ok(empty >= 20, `${empty} background pixels checked`);
  const shot = await session.run('key=3&frames=150', null);
  const picture = await screenshot(shot.page, path.join(output, 'page.png'), true);
  assert.equal(picture.width, 1180);  // the canvas: the desktop's default window
  assert.equal(picture.height, 760);
});

// The first 100 steps on the page ('.' steps once while paused) equal
// particle-lab's to 1e-9: the same engine, compiled to WebAssembly.
for (const scene of ['cloth', 'hair', 'test-chain']) {
  webTest(`FirstStepsEqualTheNativeRunner_${scene}`, async () => {
    let script = '';
    for (let k = 1; k <= 100; ++k) script += `${k} key .\n`;
    const run = await session.run(`scene=${scene}&paused&no-panel&frames=102`, script);
    assert.equal(run.exitCode, 0, run.output);
    const pane = run.state.panes[0];
    assert.equal(pane.steps, 100);
    const dir = path.join(output, `runner-${scene}`);
    fs.mkdirSync(dir, { recursive: true });
    runNative(lab, ['run', '--scene', scene, '--steps', '100', '--trajectory', 'trajectory.csv', '--every', '100'], dir);
    const rows = fs.readFileSync(path.join(dir, 'trajectory.csv'), 'utf8').trim().split('\n').slice(1)
        .map(line => line.split(',').map(Number)).filter(f => f[0] === 100);
    assert.equal(rows.length, pane.particles.length);
    let largest = 0;
    for (const [, t, i, x, y, vx, vy] of rows) {
      const p = pane.particles[i];
      largest = Math.max(largest, Math.abs(p.x[0] - x), Math.abs(p.x[1] - y), Math.abs(p.v[0] - vx), Math.abs(p.v[1] - vy));
      assert.ok(Math.abs(pane.time - t) < 1e-12);
    }
    assert.ok(largest <= 1e-9, `largest difference ${largest}`);
  });
}

// As DemoKeys.EveryScenePlusEveryIntegratorByKey…: the keys that change
// what is drawn and how it steps (forces, constraints, help, compare mode,
// build mode in and out, lockstep, dt, rewind) and q end in the state the
// desktop ends in, given the same script.
webTest('KeysEndInTheDesktopsState', async () => {
  const script = '0 key 6\n2 key f\n3 key c\n4 key h\n5 key v\n6 key +\n8 key e\n10 key e\n12 key l\n' +
                 '14 key -\n20 key b\n22 key .\n24 key v\n26 key q\n';
  const run = await session.run('lockstep&frames=500', script);
  assert.equal(run.exitCode, 0, run.output);
  const native = nativeState('keys', ['--lockstep', '--frames', '500'], script);
  assert.equal(run.state.frames, native.frames);
  assert.equal(run.state.panes.length, native.panes.length);
  run.state.panes.forEach((pane, k) => {
    const expected = native.panes[k];
    assert.equal(pane.scene, expected.scene);
    assert.equal(pane.integrator, expected.integrator);
    assert.equal(pane.dt, expected.dt);
    assert.equal(pane.steps, expected.steps);
    pane.particles.forEach((p, i) => assert.ok(distance(p.x, expected.particles[i].x) < 1e-9, `pane ${k}, particle ${i}`));
  });
  const kinds = state => (state.overlays || []).map(o => o.kind).sort().join(',');
  assert.equal(kinds(run.state), kinds(native));
});

// The browser's mouse, through Emscripten's GLUT: a press on a particle and
// a drag hold it with the mouse spring, the release lets it go, and the
// wheel turned up (away from the user) zooms in about the cursor as on the
// desktop.
webTest('TheBrowsersMouseGrabsAndTheWheelZooms', async () => {
  const page = await session.open('scene=cloth&preset=seed&param=links=4&no-panel');
  await waitFrames(page, 2);
  const pane = (await stateOf(page)).panes[0];
  const [x, y] = toPixel(pane.view, pane.particles[pane.particles.length - 1].x);
  await page.mouse.move(x, y);
  await page.mouse.down();
  for (let k = 1; k <= 10; ++k) {
    await page.mouse.move(x + 3 * k, y + 3 * k);
    await waitFrames(page, 1);
  }
  assert.equal((await stateOf(page)).panes[0].mouseSprings, 1);
  await page.mouse.up();
  await waitFrames(page, 2);
  assert.equal((await stateOf(page)).panes[0].mouseSprings, 0);
  const width = view => view.max[0] - view.min[0];
  const before = width((await stateOf(page)).panes[0].view);
  await page.mouse.wheel({ deltaY: -100 });
  await waitFrames(page, 3);
  assert.ok(width((await stateOf(page)).panes[0].view) < before / 1.1);
  await page.close();
});

// A bad option gets the desktop's one line and exit code 2, and no frame.
webTest('BadOptionIsRefusedInOneLine', async () => {
  const run = await session.run('scene=nonsense');
  assert.equal(run.exitCode, 2);
  const line = run.output.trim().split('\n')[0];
  assert.match(line, /^particle-demo: .*nonsense/);
});

// Measures the web page in headless Chromium (scripts/web-demo-times.sh runs
// it): the time from navigation to the first frame drawn, over REPEATS fresh
// loads, and each number key's scene's real-time ratio paced at 60 frames per
// second with the panel shown, as scripts/demo-frame-times.sh measures the
// desktop (simulated over wall seconds of every frame after the first, from
// the state log's real-time record). Prints CSV; no timing is asserted anywhere.
'use strict';
const { PageSession } = require('./page_driver.js');

const frames = Number(process.argv[2] || 300);
const repeats = Number(process.argv[3] || 5);
const median = values => {
  const s = [...values].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : 0.5 * (s[s.length / 2 - 1] + s[s.length / 2]);
};

(async () => {
  const session = new PageSession();
  await session.start();
  try {
    const first = [];
    for (let k = 0; k < repeats; ++k) {
      const page = await session.open('key=1');
      first.push(await page.evaluate(() => window.particleDemo.firstFrameMs));
      await page.close();
    }
    console.log(`first frame ms,${median(first).toFixed(0)},${Math.min(...first).toFixed(0)},${Math.max(...first).toFixed(0)}`);
    const scenes = ['key=1', 'key=2', 'key=3', 'key=4', 'key=5', 'key=6', 'key=7', 'key=8', 'key=9', 'key=0',
                    'scene=cloth&param=width=64&param=height=64&param=links=8'];
    for (const scene of scenes) {
      const run = await session.run(`${scene}&frames=${frames}&realtime`, null, 600000);
      const r = run.state.realTime;
      console.log(`${scene},${(r.simSeconds / r.wallSeconds).toFixed(3)}`);
      await run.page.close();
    }
  } finally {
    await session.stop();
  }
})().catch(error => {
  console.error(error);
  process.exit(1);
});

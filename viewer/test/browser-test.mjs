// The viewer in a real browser: Debian's chromium, headless with software WebGL (SwiftShader),
// driven by playwright-core. Serves REPLAY with `TUMBLE view`, then checks that the scene graph
// holds the file's bodies and threads, that scrubbing and stepping show the file's poses, that
// clicking a body shows its figures, and that the drawing is not blank; saves a screenshot.
//
//   node viewer/test/browser-test.mjs TUMBLE REPLAY SCREENSHOT.png
import { readFileSync } from 'node:fs';
import { load, openBrowser, serve } from './browser.mjs';
import { parseReplay, POSE_FLOATS } from '../src/replay.js';

const [tumble, replayPath, screenshot] = process.argv.slice(2);
const replay = parseReplay(readFileSync(replayPath).buffer);
let failures = 0;
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures++;
}

/// The frame's pose of `body` in the file against the scene graph's (to float precision).
async function expectPose(page, frame, body, what) {
  const shown = await page.evaluate((b) => tumbleViewer.world.bodies[b].position.toArray(), body);
  const p = replay.frames[frame].poses;
  const error = Math.max(...shown.map((x, k) => Math.abs(x - p[body * POSE_FLOATS + k])));
  check(error < 1e-6, `${what}: body ${body} at frame ${frame} is where the file puts it (error ${error})`);
}

/// The scene graph holds a group per body of the file and a segment per thread.
async function checkCounts(page) {
  const d = replay.description;
  const counts = await page.evaluate(() => ({
    bodies: tumbleViewer.scene.children.filter((o) => /^body \d+$/.test(o.name)).length,
    threads: tumbleViewer.world.threads.geometry.attributes.position.count / 2,
  }));
  check(counts.bodies === d.bodies.length, `${counts.bodies} body groups for the file's ${d.bodies.length} bodies`);
  check(counts.threads === d.springs.length, `${counts.threads} thread segments for ${d.springs.length} springs`);
}

/// Scrubs with the slider to the middle frame, then steps forward with the button; returns the
/// frame shown.
async function checkScrubAndStep(page) {
  const middle = Math.floor(replay.frames.length / 2);
  await page.$eval('#scrub', (e, v) => {
    e.value = String(v);
    e.dispatchEvent(new Event('input'));
  }, middle);
  const moving = replay.description.bodies.findIndex((b) => b.type === 'dynamic');
  await expectPose(page, middle, 0, 'scrub');
  await expectPose(page, middle, moving, 'scrub');
  await page.click('#stepForward');
  check((await page.evaluate(() => tumbleViewer.player.frame)) === middle + 1, 'the step button shows the next frame');
  await expectPose(page, middle + 1, moving, 'step');
  return middle + 1;
}

/// Clicks the first dynamic body whose centre nothing hides; the panel names it, its mass and
/// its speed at `frame` in the file.
async function checkClick(page, frame) {
  const target = await page.evaluate(() => {
    const { world, view, THREE } = tumbleViewer;
    const rect = view.renderer.domElement.getBoundingClientRect();
    const ray = new THREE.Raycaster();
    for (const group of world.bodies) {
      const b = group.userData.index;
      if (tumbleViewer.replay.description.bodies[b].type !== 'dynamic') continue;
      const ndc = group.position.clone().project(view.camera);
      if (Math.abs(ndc.x) > 0.9 || Math.abs(ndc.y) > 0.9) continue;
      ray.setFromCamera(new THREE.Vector2(ndc.x, ndc.y), view.camera);
      const hit = ray.intersectObjects(world.bodies, true).find((h) => h.object.userData.body !== undefined);
      if (hit?.object.userData.body === b)
        return { body: b, x: rect.left + ((ndc.x + 1) / 2) * rect.width, y: rect.top + ((1 - ndc.y) / 2) * rect.height };
    }
    return null;
  });
  check(target !== null, 'a dynamic body is in view to click');
  if (!target) return;
  await page.mouse.click(target.x, target.y);
  const info = await page.textContent('#info');
  const p = replay.frames[frame].poses;
  const o = target.body * POSE_FLOATS;
  const speed = Math.hypot(p[o + 7], p[o + 8], p[o + 9]);
  check(info.startsWith(`body ${target.body}`), `clicking body ${target.body} names it: ${JSON.stringify(info.split('\n')[0])}`);
  check(info.includes(`${replay.description.bodies[target.body].mass.toPrecision(4)} kg`), 'the panel shows its mass');
  check(info.includes(`${speed.toPrecision(4)} m/s`), `the panel shows its speed in the file (${speed.toPrecision(4)} m/s)`);
}

/// Software WebGL can fall back to an empty canvas: the picture's luminance must vary.
async function checkNotBlank(page) {
  const pixels = await page.evaluate(() => {
    const canvas = tumbleViewer.view.renderer.domElement;
    tumbleViewer.view.renderer.render(tumbleViewer.scene, tumbleViewer.view.camera);
    const copy = Object.assign(document.createElement('canvas'), { width: canvas.width, height: canvas.height });
    const c = copy.getContext('2d');
    c.drawImage(canvas, 0, 0);
    const data = c.getImageData(0, 0, copy.width, copy.height).data;
    let sum = 0;
    let sum2 = 0;
    for (let i = 0; i < data.length; i += 4) {
      const y = 0.3 * data[i] + 0.59 * data[i + 1] + 0.11 * data[i + 2];
      sum += y;
      sum2 += y * y;
    }
    const n = data.length / 4;
    return { n, deviation: Math.sqrt(Math.max(sum2 / n - (sum / n) ** 2, 0)) };
  });
  check(pixels.deviation > 8, `the drawing is not blank (luminance deviation ${pixels.deviation.toFixed(1)} over ${pixels.n} pixels)`);
}

async function main() {
  const { server, url } = await serve(tumble, replayPath);
  const { context, close } = await openBrowser();
  try {
    const page = context.pages()[0] ?? (await context.newPage());
    page.on('pageerror', (e) => check(false, `page error: ${e.message}`));
    const state = await load(page, url);
    check(state === 'ready', `the page drew the replay (state ${state}: ${await page.textContent('#error')})`);
    if (state !== 'ready') return;
    await checkCounts(page);
    const frame = await checkScrubAndStep(page);
    await page.check('#showContacts');
    await page.check('#showTrails');
    await checkClick(page, frame);
    await checkNotBlank(page);
    await page.screenshot({ path: screenshot });
    console.log(`screenshot: ${screenshot}`);
  } finally {
    await close();
    server.kill();
  }
}

main()
  .catch((e) => check(false, e.stack))
  .finally(() => {
    console.log(`${failures === 0 ? 'passed' : `${failures} checks failed`}`);
    process.exit(failures === 0 ? 0 : 1);
  });

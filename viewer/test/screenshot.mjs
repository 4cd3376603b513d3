// A screenshot of the viewer on a replay at a moment, for the documentation:
//   node viewer/test/screenshot.mjs TUMBLE REPLAY OUT.png TIME [contacts] [trails]
import { load, openBrowser, serve } from './browser.mjs';

const [tumble, replay, out, time, ...toggles] = process.argv.slice(2);
const { server, url } = await serve(tumble, replay);
const { context, close } = await openBrowser({ width: 1000, height: 640 });
try {
  const page = context.pages()[0] ?? (await context.newPage());
  if ((await load(page, url)) !== 'ready') throw new Error(await page.textContent('#error'));
  for (const t of toggles) await page.check(`#show${t[0].toUpperCase()}${t.slice(1)}`);
  await page.evaluate((t) => {
    const { player } = tumbleViewer;
    const i = player.replay.frames.findIndex((f) => f.time >= t - 1e-9);
    player.setFrame(i < 0 ? player.replay.frames.length - 1 : i);
  }, Number(time));
  await page.waitForTimeout(300);
  await page.screenshot({ path: out });
  console.log(`screenshot: ${out}`);
} finally {
  await close();
  server.kill();
}

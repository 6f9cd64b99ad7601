// Times `strahl view` in headless Chromium on the real clock (docs/PERFORMANCE.md, *The
// viewer*): the frame time while orbiting, and the time from a move to the preview and to
// the final solution on screen. Run by scripts/view-timing.sh, which starts the viewer and
// installs playwright-core; arguments: the viewer's address, the frames to orbit, the
// object or light to move and the offset (NAME:X,Y,Z); MOVES in the environment: how many
// moves, there and back (3).
import { chromium } from "playwright-core";

const [address, frames, move] = process.argv.slice(2);
const browser = await chromium.launch({
  executablePath: process.env.STRAHL_CHROMIUM || "/usr/bin/chromium",
  args: ["--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--no-sandbox",
         "--disable-background-networking", "--disable-component-update"],
});
const page = await browser.newPage({ viewport: { width: 800, height: 600 } });
await page.goto(`http://${address}/?orbit=${frames}`);
await page.waitForSelector("#frames[data-mean-ms]", { timeout: 600_000 });
console.log("orbit:", await page.textContent("#frames"));
const [name, by] = move.split(":");
const [x, y, z] = by.split(",");
for (let k = 0; k < Number(process.env.MOVES || 3); k++) {
  await page.selectOption("#move-what", name);
  const sign = k % 2 === 0 ? 1 : -1;
  await page.fill("#move-x", String(sign * x));
  await page.fill("#move-y", String(sign * y));
  await page.fill("#move-z", String(sign * z));
  await page.click("#move");
  await page.waitForSelector("#timing[data-final]", { timeout: 600_000 });
  console.log(`move ${k + 1}:`, await page.textContent("#timing"));
}
await browser.close();

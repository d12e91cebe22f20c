// The page `graspkit view` writes, opened in a real browser (headless Chromium through
// puppeteer-core, WebGL on SwiftShader): no console errors; the object is drawn where the page's
// camera projects its centre (its colour there, the background in the corners); stepping to
// grasp 2 changes the hand's pixels, and stepping back draws grasp 1 again. A simulation played
// back (view --trajectory) ends with every body where the run's final world (simulate --out) has
// it, the Barrett's broken-away fingers included.
// Usage: node view_page.cjs WORLD_PAGE.html PLAN_PAGE.html CHROMIUM OUT_DIR RUN_PAGE FINAL_PAGE
const puppeteer = require('puppeteer-core');
const path = require('node:path');

const [worldPage, planPage, chromium, outDir, runPage, finalPage] = process.argv.slice(2);

function fail(message) {
  console.error(`view_page: FAILED: ${message}`);
  process.exit(1);
}

async function open(browser, file, errors) {
  const page = await browser.newPage();
  await page.setViewport({ width: 800, height: 600 });
  page.on('console', (m) => { if (m.type() === 'error') errors.push(`${file}: ${m.text()}`); });
  page.on('pageerror', (e) => errors.push(`${file}: ${e.message}`));
  await page.goto(`file://${path.resolve(file)}`);
  await page.waitForFunction('window.graspkitViewer && window.graspkitViewer.ready', { timeout: 30000 });
  return page;
}

// The canvas's pixels (RGBA rows, top first), read through a 2-D canvas.
async function pixels(page) {
  return page.evaluate(() => {
    const gl = document.getElementById('view');
    const copy = document.createElement('canvas');
    copy.width = gl.width;
    copy.height = gl.height;
    const context = copy.getContext('2d');
    context.drawImage(gl, 0, 0);
    return { width: copy.width, height: copy.height,
             data: Array.from(context.getImageData(0, 0, copy.width, copy.height).data) };
  });
}

function at(image, x, y) {
  const i = (Math.round(y) * image.width + Math.round(x)) * 4;
  return image.data.slice(i, i + 3);
}

(async () => {
  const browser = await puppeteer.launch({
    executablePath: chromium,
    headless: true,
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  });
  const errors = [];
  try {
    // The world page: the mug at the projection of its centre, white corners.
    const page = await open(browser, worldPage, errors);
    await page.screenshot({ path: path.join(outDir, 'world_page.png') });
    const meta = JSON.parse(await page.$eval('#graspkit-meta', (e) => e.textContent));
    if (!meta.object) fail('the world page names no object');
    const [x, y] = await page.evaluate((c) => window.graspkitViewer.project(c), meta.object.centre);
    const image = await pixels(page);
    if (!(x > 0 && x < image.width && y > 0 && y < image.height))
      fail(`the object's centre projects off the canvas: ${x}, ${y}`);
    const centre = at(image, x, y);
    // The mug is glass: blue above red, and not the white background.
    if (!(centre[2] > centre[0] + 20 && centre[0] < 240))
      fail(`the pixel at the object's centre (${x.toFixed(1)}, ${y.toFixed(1)}) is ${centre}, not the object's colour`);
    for (const [cx, cy] of [[2, image.height - 3], [image.width - 3, image.height - 3]]) {
      const corner = at(image, cx, cy);
      if (corner.some((v) => v < 250)) fail(`corner ${cx},${cy} is ${corner}, not the background`);
    }

    // The plan page: stepping changes the picture where the hand moved, and back restores it.
    const plan = await open(browser, planPage, errors);
    const count = await plan.evaluate(() => window.graspkitViewer.count);
    if (count < 2) fail(`the plan page holds ${count} grasps; the test needs 2`);
    const first = await pixels(plan);
    await plan.evaluate(() => window.graspkitViewer.show(1));
    const second = await pixels(plan);
    await plan.screenshot({ path: path.join(outDir, 'plan_page_grasp2.png') });
    await plan.click('#previous');
    const again = await pixels(plan);
    const label = await plan.$eval('#name', (e) => e.textContent);
    let changed = 0, restored = 0;
    for (let i = 0; i < first.data.length; i += 4) {
      const differs = (a, b) => Math.abs(a.data[i] - b.data[i]) + Math.abs(a.data[i + 1] - b.data[i + 1]) +
        Math.abs(a.data[i + 2] - b.data[i + 2]) > 30;
      if (differs(first, second)) ++changed;
      if (differs(first, again)) ++restored;
    }
    const total = first.data.length / 4;
    if (changed < 0.01 * total) fail(`grasp 2 changed ${changed} of ${total} pixels`);
    if (restored > 0.001 * total) fail(`back at grasp 1, ${restored} pixels differ from the first view`);
    if (!label.startsWith('grasp 1 ')) fail(`the panel says '${label}' after stepping back`);
    // The simulation played to its end: every body where the final world has it.
    const run = await open(browser, runPage, errors);
    const final = await open(browser, finalPage, errors);
    const frameCount = await run.evaluate(() => window.graspkitViewer.frames);
    if (frameCount < 10) fail(`the run page holds ${frameCount} frames`);
    const bodies = ['mug', 'Barrett_chain0_link1', 'Barrett_chain0_link2', 'Barrett_chain2_link1'];
    const firstFrame = {};
    await run.evaluate(() => window.graspkitViewer.seek(0));
    for (const name of bodies) firstFrame[name] = await run.evaluate((n) => window.graspkitViewer.bodyPosition(n), name);
    await run.evaluate((k) => window.graspkitViewer.seek(k), frameCount - 1);
    let moved = 0;
    for (const name of bodies) {
      const played = await run.evaluate((n) => window.graspkitViewer.bodyPosition(n), name);
      const expected = await final.evaluate((n) => window.graspkitViewer.bodyPosition(n), name);
      if (!played || !expected) fail(`no body '${name}' on the pages`);
      const gap = Math.hypot(...played.map((v, i) => v - expected[i]));
      if (gap > 1e-6) fail(`at the run's end '${name}' is drawn ${gap * 1000} mm from the final world's`);
      moved = Math.max(moved, Math.hypot(...played.map((v, i) => v - firstFrame[name][i])));
    }
    if (moved < 0.005) fail(`nothing moved more than ${moved * 1000} mm in the run`);
    if (errors.length) fail(`console errors:\n${errors.join('\n')}`);
    console.log(`view_page: ok: object at ${x.toFixed(1)},${y.toFixed(1)} is ${centre}; ` +
                `grasp 2 changed ${changed} of ${total} pixels`);
  } finally {
    await browser.close();
  }
})().catch((e) => fail(e.stack || e));

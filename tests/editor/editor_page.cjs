// graspkit serve driven as a user drives it, in headless Chromium (puppeteer-core): every
// request without the token is refused; the hand dragged into the mug shows the collision and
// dragged back out clears it; autograsp shows the epsilon `graspkit grasp --autograsp` prints for
// the same pose; a DOF slider changes the contacts; the saved world, loaded by the CLI, gives the
// same grasp; the copied Lua sets the same hand; a 2 s plan runs while the server keeps answering
// and the page steps through its grasps; validation gives the CLI's labels; files outside the
// allowed folders are refused and a malformed request leaves the world as it was. Screenshots
// go to OUT_DIR (docs/editor.md shows them).
// Usage: node editor_page.cjs GRASPKIT WORLD CHROMIUM OUT_DIR
const puppeteer = require('puppeteer-core');
const { spawn, execFileSync } = require('node:child_process');
const fs = require('node:fs');
const path = require('node:path');

const [graspkit, worldFile, chromium, outDir] = process.argv.slice(2);
let server = null;

function fail(message) {
  console.error(`editor_page: FAILED: ${message}`);
  if (server) server.kill('SIGTERM');
  process.exit(1);
}

function check(condition, message) {
  if (!condition) fail(message);
}

function cli(args) {
  return execFileSync(graspkit, ['-q', ...args], { encoding: 'utf8', maxBuffer: 1 << 26 });
}

function startServer() {
  return new Promise((resolve, reject) => {
    server = spawn(graspkit, ['-q', 'serve', worldFile, '--port', '0', '--allow-write', outDir],
      { stdio: ['ignore', 'pipe', 'inherit'] });
    let text = '';
    server.stdout.on('data', (chunk) => {
      text += chunk;
      const match = text.match(/(http:\/\/127\.0\.0\.1:\d+\/)\?token=([0-9a-f]+)/);
      if (match) resolve({ base: match[1], token: match[2] });
    });
    server.on('exit', (code) => reject(new Error(`graspkit serve exited with ${code}`)));
    setTimeout(() => reject(new Error('graspkit serve printed no address in 30 s')), 30000);
  });
}

async function status(url, options = {}) {
  const response = await fetch(url, options);
  return response.status;
}

// Strongly red pixels of the canvas: colliding links glow red.
async function redPixels(page) {
  return page.evaluate(() => {
    const gl = document.getElementById('view');
    const copy = document.createElement('canvas');
    copy.width = gl.width;
    copy.height = gl.height;
    const context = copy.getContext('2d');
    context.drawImage(gl, 0, 0);
    const data = context.getImageData(0, 0, copy.width, copy.height).data;
    let red = 0;
    for (let i = 0; i < data.length; i += 4)
      if (data[i] > 180 && data[i + 1] < 90 && data[i + 2] < 90) ++red;
    return red;
  });
}

const editor = (page, body, ...args) => page.evaluate(body, ...args);
const relative = (a, b) => Math.abs(a - b) / Math.max(1e-12, Math.abs(b));

(async () => {
  // A grasp to start from: the pre-grasp pose and DOFs of a short plan's best grasp.
  const planFile = path.join(outDir, 'start_plan.json');
  cli(['plan', worldFile, '--steps', '1500', '--threads', '1', '--seed', '3', '--top', '3', '--out', planFile]);
  const best = JSON.parse(fs.readFileSync(planFile, 'utf8')).grasps[0];
  const pregrasp = { translation: best.pose.world.translation, quaternion: best.pose.world.quaternion, dofs: best.dofs };

  const { base, token } = await startServer();
  // Refused without the token, with a wrong one, and for another host name.
  check(await status(`${base}`) === 403, 'the page was served without the token');
  check(await status(`${base}api/state`, { method: 'POST', body: '{}' }) === 403, 'state without the token');
  check(await status(`${base}api/scene.glb?token=${'0'.repeat(32)}`) === 403, 'a wrong token was taken');
  check(await status(`${base}api/pose`, { method: 'POST', body: '{"translation":[0,0,0],"quaternion":[1,0,0,0]}',
    headers: { 'X-Graspkit-Token': 'x' } }) === 403, 'pose with a bad token');

  const browser = await puppeteer.launch({
    executablePath: chromium, headless: true,
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  });
  const errors = [];
  try {
    const page = await browser.newPage();
    await page.setViewport({ width: 1100, height: 700 });
    // The refusals the test asks for show as failed loads; each is checked where it is made.
    page.on('console', (m) => {
      if (m.type() === 'error' && !m.text().startsWith('Failed to load resource')) errors.push(m.text());
    });
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(`${base}?token=${token}`);
    await page.waitForFunction('window.graspkitEditor && window.graspkitEditor.ready', { timeout: 60000 });
    const start = await editor(page, () => window.graspkitEditor.state);
    // What a measure at rest uses: GraspIt!'s qhull, as graspkit grasp.
    const closedMethod = start.quality.method;
    check(closedMethod.includes('GraspIt'), `the state is measured by ${closedMethod}`);
    const mug = start.bodies[start.object].t.map((v) => v * 1000);
    check(start.collisions.length === 0, `the world starts with collisions: ${JSON.stringify(start.collisions)}`);
    const redBefore = await redPixels(page);

    // A real drag of the on-screen handle: the mouse on the handle's centre (the free move in the
    // view plane), 60 px to the right; the hand moves, and the drag is one undo step.
    const [hx, hy] = await editor(page, (t) => window.graspkitEditor.project(t.map((v) => v / 1000)),
      start.hand.pose.translation);
    await page.mouse.move(hx, hy);
    await page.mouse.down();
    for (let i = 1; i <= 6; ++i) await page.mouse.move(hx + 10 * i, hy, { steps: 2 });
    await page.mouse.up();
    await editor(page, () => window.graspkitEditor.idle());
    const dragged = await editor(page, () => window.graspkitEditor.state);
    const shift = Math.hypot(...dragged.hand.pose.translation.map((v, i) => v - start.hand.pose.translation[i]));
    check(shift > 1, `dragging the handle moved the hand ${shift} mm`);
    check(dragged.undo === start.undo + 1, `the mouse drag made ${dragged.undo - start.undo} undo steps, not 1`);
    check(dragged.quality.method === closedMethod, `after the drag the grasp was measured by ${dragged.quality.method}`);
    await page.click('#undo');
    await editor(page, () => window.graspkitEditor.idle());
    const back = await editor(page, () => window.graspkitEditor.state);
    check(JSON.stringify(back.hand.pose) === JSON.stringify(start.hand.pose), 'undo did not undo the mouse drag');

    // Into the mug: the collision is shown (listed, and the links glow red); one undo step.
    await editor(page, (to) => window.graspkitEditor.drag(to), mug);
    const inside = await editor(page, () => window.graspkitEditor.state);
    check(inside.collisions.length > 0, 'the hand inside the mug reports no collision');
    const collisionText = await page.$eval('#collisions', (e) => e.textContent);
    check(collisionText.startsWith('collisions:'), `the panel says '${collisionText}' inside the mug`);
    const redInside = await redPixels(page);
    check(redInside > redBefore + 200, `colliding links are not drawn red (${redBefore} -> ${redInside} red pixels)`);
    check(inside.undo === back.undo + 1, `a drag made ${inside.undo - back.undo} undo steps, not 1`);
    await page.screenshot({ path: path.join(outDir, 'editor_collision.png') });
    // And back out.
    await editor(page, (to) => window.graspkitEditor.drag(to), start.hand.pose.translation);
    const out = await editor(page, () => window.graspkitEditor.state);
    check(out.collisions.length === 0, `back out, collisions remain: ${JSON.stringify(out.collisions)}`);
    check((await page.$eval('#collisions', (e) => e.textContent)) === 'no collisions', 'the panel still shows collisions');
    // Undo takes the hand back into the mug, redo out again.
    await page.click('#undo');
    await editor(page, () => window.graspkitEditor.idle());
    const undone = await editor(page, () => window.graspkitEditor.state);
    check(JSON.stringify(undone.hand.pose) === JSON.stringify(inside.hand.pose), 'undo did not restore the pose inside the mug');
    await page.click('#redo');
    await editor(page, () => window.graspkitEditor.idle());
    const redone = await editor(page, () => window.graspkitEditor.state);
    check(JSON.stringify(redone.hand.pose) === JSON.stringify(out.hand.pose) && redone.collisions.length === 0,
      'redo did not bring the hand back out');

    // Autograsp from the plan's pre-grasp: the epsilon `graspkit grasp --autograsp` gives.
    await editor(page, (p) => window.graspkitEditor.drag(p.translation, p.quaternion), pregrasp);
    const open = await editor(page, (p) => window.graspkitEditor.act('dofs', { values: p.dofs }), pregrasp);
    check(open.collisions.length === 0, `the pre-grasp collides: ${JSON.stringify(open.collisions)}`);
    await page.click('#autograsp');
    await editor(page, () => window.graspkitEditor.idle());
    const closed = await editor(page, () => window.graspkitEditor.state);
    const pose = open.hand.pose;
    const expected = JSON.parse(cli(['grasp', worldFile, '--pose', [...pose.translation, ...pose.quaternion].join(','),
      '--dofs', open.hand.dofs.map((d) => d.value).join(','), '--autograsp', '--json']));
    check(expected.epsilon > 0, `the test's grasp is not force closure (epsilon ${expected.epsilon})`);
    check(relative(closed.quality.epsilon, expected.epsilon) < 1e-9,
      `autograsp's epsilon ${closed.quality.epsilon}, graspkit grasp --autograsp's ${expected.epsilon}`);
    check(closed.contacts.length === expected.contacts.length,
      `autograsp found ${closed.contacts.length} contacts, the CLI ${expected.contacts.length}`);
    const qualityText = await page.$eval('#quality', (e) => e.textContent);
    check(qualityText.includes(`epsilon ${expected.epsilon.toPrecision(5)}`),
      `the panel says '${qualityText}', not epsilon ${expected.epsilon.toPrecision(5)}`);
    await page.screenshot({ path: path.join(outDir, 'editor_autograsp.png') });

    // A DOF slider: finger 1 opened, its contacts go.
    const dof = closed.hand.dofs[1];
    await page.$eval('#dof-1', (range, value) => {
      range.value = String(value);
      range.dispatchEvent(new Event('input'));
      range.dispatchEvent(new Event('change'));
    }, dof.min + 0.2 * (dof.value - dof.min));
    await editor(page, () => window.graspkitEditor.idle());
    const slid = await editor(page, () => window.graspkitEditor.state);
    // The slider moves in 500 steps over the range.
    check(Math.abs(slid.hand.dofs[1].value - (dof.min + 0.2 * (dof.value - dof.min))) <= (dof.max - dof.min) / 500,
      `the slider set DOF 1 to ${slid.hand.dofs[1].value}`);
    check(slid.contacts.length < closed.contacts.length,
      `opening DOF 1 left ${slid.contacts.length} contacts of ${closed.contacts.length}`);

    // Save, and load the file with the CLI: the same DOFs, contacts and epsilon.
    const saved = path.join(outDir, 'saved_world.xml');
    await page.$eval('#save-file', (input, file) => { input.value = file; }, saved);
    await page.click('#save');
    await editor(page, () => window.graspkitEditor.idle());
    check(fs.existsSync(saved), 'Save world wrote no file');
    const reloaded = JSON.parse(cli(['grasp', saved, '--json']));
    slid.hand.dofs.forEach((d, i) => check(Math.abs(reloaded.dof_values[i] - d.value) < 1e-9,
      `saved DOF ${i}: ${reloaded.dof_values[i]} vs ${d.value}`));
    check(reloaded.contacts.length === slid.contacts.length,
      `the saved world has ${reloaded.contacts.length} contacts, the page ${slid.contacts.length}`);
    check(reloaded.epsilon === slid.quality.epsilon || relative(reloaded.epsilon, slid.quality.epsilon) < 1e-9,
      `the saved world's epsilon ${reloaded.epsilon}, the page's ${slid.quality.epsilon}`);

    // Copy as Lua: the script sets the hand the page shows.
    await page.click('#copy-lua');
    await editor(page, () => window.graspkitEditor.idle());
    const lua = await page.$eval('#script', (e) => e.value);
    const script = path.join(outDir, 'copied.lua');
    fs.writeFileSync(script, `${lua}print(table.concat(hand:dofs(), ","))\n`);
    const dofsFromLua = cli(['run', script, '--allow-read', path.dirname(path.dirname(worldFile))]).trim().split(',').map(Number);
    slid.hand.dofs.forEach((d, i) => check(Math.abs(dofsFromLua[i] - d.value) < 1e-12,
      `the copied Lua sets DOF ${i} to ${dofsFromLua[i]}, the page shows ${d.value}`));

    // Save picture: the engine's renderer, from the page's camera, the object in the middle.
    const picture = path.join(outDir, 'picture.png');
    await page.$eval('#picture-file', (input, file) => { input.value = file; }, picture);
    await page.click('#save-picture');
    await editor(page, () => window.graspkitEditor.idle());
    check(fs.existsSync(picture) && fs.readFileSync(picture).subarray(1, 4).toString() === 'PNG',
      'Save picture wrote no PNG');

    // Outside the allowed folders: refused, nothing written; the world is unchanged.
    const outside = `/tmp/graspkit-editor-outside-${process.pid}.xml`;
    const refusal = await editor(page, (file) => window.graspkitEditor.request('save', { file })
      .then(() => 'saved', (e) => e.message), outside);
    check(refusal !== 'saved' && !fs.existsSync(outside), `a save outside the allowed folders: ${refusal}`);
    const readRefusal = await editor(page, () => window.graspkitEditor.request('load', { file: '/etc/hostname' })
      .then(() => 'loaded', (e) => e.message));
    check(readRefusal !== 'loaded', 'a world outside the roots was loaded');
    const before = await editor(page, () => window.graspkitEditor.request('state'));
    const malformed = await editor(page, () => window.graspkitEditor.request('pose', { translation: [1, 2] })
      .then(() => 'taken', (e) => e.message));
    check(malformed.includes('translation'), `a malformed pose was answered '${malformed}'`);
    const after = await editor(page, () => window.graspkitEditor.request('state'));
    check(JSON.stringify(after.hand) === JSON.stringify(before.hand), 'a malformed request changed the hand');

    // Plan for 2 s; the server keeps answering meanwhile; step through the grasps.
    // Every energy the page offers is one the planner knows.
    const energies = await page.$$eval('#plan-energy option', (options) => options.map((o) => o.value));
    const known = cli(['plan', '--help']);
    for (const energy of energies) check(known.includes(energy), `the page offers energy '${energy}' plan does not know`);
    await page.$eval('#plan-seconds', (input) => { input.value = '2'; });
    await page.click('#plan');
    let slowest = 0;
    for (let i = 0; i < 6; ++i) {
      const took = await editor(page, async () => {
        const t0 = performance.now();
        await window.graspkitEditor.request('state');
        return performance.now() - t0;
      });
      slowest = Math.max(slowest, took);
      await new Promise((r) => setTimeout(r, 200));
    }
    check(slowest < 1000, `a state request took ${slowest.toFixed(0)} ms during the plan`);
    await page.waitForFunction('window.graspkitEditor.planDone === true', { timeout: 60000 });
    const planText = await page.$eval('#plan-text', (e) => e.textContent);
    const grasps = await editor(page, () => window.graspkitEditor.grasps);
    check(grasps.length >= 2, `the plan gave ${grasps.length} grasps (${planText})`);
    await editor(page, () => window.graspkitEditor.idle());
    const first = await editor(page, () => window.graspkitEditor.state);
    check((await page.$eval('#grasp-name', (e) => e.textContent)).startsWith('grasp 1 (1 of'), 'grasp 1 is not shown');
    await page.screenshot({ path: path.join(outDir, 'editor_plan.png') });
    await page.click('#grasp-next');
    await editor(page, () => window.graspkitEditor.idle());
    await page.waitForFunction('window.graspkitEditor.graspIndex === 1');
    const second = await editor(page, () => window.graspkitEditor.state);
    check((await page.$eval('#grasp-name', (e) => e.textContent)).startsWith('grasp 2 (2 of'), 'grasp 2 is not shown');
    check(JSON.stringify(second.hand.pose) !== JSON.stringify(first.hand.pose), 'grasp 2 has grasp 1\'s pose');
    check(Math.abs(second.quality.epsilon - grasps[1].epsilon) < 1e-9 * Math.max(1, Math.abs(grasps[1].epsilon)),
      `grasp 2 shows epsilon ${second.quality.epsilon}, the plan measured ${grasps[1].epsilon}`);

    // Validate grasp 2: the labels `graspkit validate` gives for the same world.
    const graspFile = path.join(outDir, 'grasp2.xml');
    await editor(page, (file) => window.graspkitEditor.act('save', { file }), graspFile);
    await page.click('#validate');
    await page.waitForFunction(() => /held/.test(document.getElementById('validation').textContent), { timeout: 120000 });
    const label = await editor(page, () => window.graspkitEditor.validation);
    const cliLabel = JSON.parse(cli(['validate', graspFile, '--json'])).grasps[0];
    check(JSON.stringify(label.directions.map((d) => d.held)) === JSON.stringify(cliLabel.directions.map((d) => d.held)),
      `the page's labels ${JSON.stringify(label.directions.map((d) => d.held))} differ from the CLI's`);
    await page.click('#play');
    await page.waitForFunction('window.graspkitEditor.playedFrames > 10', { timeout: 60000 });

    if (errors.length) fail(`console errors:\n${errors.join('\n')}`);
    console.log(`editor_page: ok: ${inside.collisions.length} colliding pairs inside the mug; autograsp epsilon ` +
      `${closed.quality.epsilon} as the CLI; ${grasps.length} grasps planned (slowest request while planning ` +
      `${slowest.toFixed(0)} ms); validation ${label.held ? 'held' : 'not held'} as the CLI`);
  } finally {
    await browser.close();
    server.kill('SIGTERM');
  }
})().catch((e) => fail(e.stack || e));

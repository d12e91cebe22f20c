// The graspkit serve page: the world from the server (binary glTF, one node per body), the hand
// moved with on-screen handles or typed values, its DOFs and eigengrasps on sliders, and every
// engine action through the server's JSON API (docs/editor.md). The server holds the world; the
// page shows the state each answer carries. Bundled with three.js at build time: no network.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { TransformControls } from 'three/addons/controls/TransformControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

const token = new URLSearchParams(window.location.search).get('token') || '';

async function request(action, args = {}) {
  const response = await fetch(`/api/${action}`, {
    method: 'POST',
    headers: { 'Content-Type': 'application/json', 'X-Graspkit-Token': token },
    body: JSON.stringify(args),
  });
  const answer = await response.json().catch(() => ({ error: `HTTP ${response.status}` }));
  if (!response.ok) throw new Error(answer.error || `HTTP ${response.status}`);
  return answer;
}

function element(tag, attributes = {}, children = []) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attributes)) {
    if (key === 'text') node.textContent = value;
    else if (key.startsWith('on')) node.addEventListener(key.slice(2), value);
    else node.setAttribute(key, value);
  }
  for (const child of children) node.append(child);
  return node;
}

function format(value, digits = 5) {
  if (value === null || value === undefined) return '—';  // not measured (NaN in the engine)
  if (typeof value !== 'number') return String(value);
  return Number.isInteger(value) ? String(value) : value.toPrecision(digits);
}

// A contact: a small sphere at the point and its friction cone as thin lines (rim and four
// generators), apex at the point, opening along the normal with half angle atan(mu).
function contactMarker(contact, size) {
  const group = new THREE.Group();
  const point = new THREE.Vector3(...contact.point);
  const normal = new THREE.Vector3(...contact.normal).normalize();
  const sphere = new THREE.Mesh(new THREE.SphereGeometry(size * 0.12, 12, 8),
    new THREE.MeshBasicMaterial({ color: 0xd01010, depthTest: false }));
  sphere.renderOrder = 3;
  group.add(sphere);
  const radius = size * Math.max(contact.mu, 0.01);
  const lines = [];
  const rim = 24;
  for (let i = 0; i < rim; ++i) {
    const a = (i / rim) * 2 * Math.PI, b = ((i + 1) / rim) * 2 * Math.PI;
    lines.push(radius * Math.cos(a), size, radius * Math.sin(a), radius * Math.cos(b), size, radius * Math.sin(b));
  }
  for (let i = 0; i < 4; ++i) {
    const a = (i / 4) * 2 * Math.PI;
    lines.push(0, 0, 0, radius * Math.cos(a), size, radius * Math.sin(a));
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(lines, 3));
  const cone = new THREE.LineSegments(geometry,
    new THREE.LineBasicMaterial({ color: 0xc03000, depthTest: false }));
  cone.renderOrder = 2;
  cone.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), normal);
  group.add(cone);
  group.position.copy(point);
  return group;
}

function start() {
  const canvas = document.getElementById('view');
  const side = document.getElementById('side');
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  const world = new THREE.Scene();
  world.background = new THREE.Color(0xffffff);
  world.add(new THREE.HemisphereLight(0xffffff, 0x666666, 1.6));
  const camera = new THREE.PerspectiveCamera(40, 1, 0.001, 100);
  const headlight = new THREE.DirectionalLight(0xffffff, 1.8);
  headlight.position.set(-0.4, 0.6, 1.0);
  camera.add(headlight);
  world.add(camera);
  const orbit = new OrbitControls(camera, canvas);
  const handle = new THREE.Object3D();  // the hand's base frame, what the handles move
  world.add(handle);
  const gizmo = new TransformControls(camera, canvas);
  gizmo.attach(handle);
  gizmo.setSize(0.8);
  world.add(gizmo.getHelper());

  const nodes = new Map();  // body name -> glTF node
  const markers = new THREE.Group();
  world.add(markers);
  const editor = {
    ready: false, state: null, pending: 0, errors: [], grasps: [], graspIndex: -1,
    markerSize: 0.02, playing: false,
  };

  // ---- the side panel ----
  const ui = {};
  const message = element('div', { id: 'message' });
  function say(text, bad = false) {
    message.textContent = text;
    message.className = bad ? 'bad' : '';
  }
  function number(id, step) {
    ui[id] = element('input', { id, type: 'number', step: String(step) });
    return ui[id];
  }
  ui.title = element('div', { id: 'title' });
  ui.position = ['x', 'y', 'z'].map((axis) => number(`hand-${axis}`, 1));
  ui.rotation = ['rx', 'ry', 'rz'].map((axis) => number(`hand-${axis}`, 1));
  ui.snap = element('input', { id: 'snap', type: 'checkbox' });
  ui.dofs = element('div', { id: 'dofs' });
  ui.eigen = element('div', { id: 'eigengrasps' });
  ui.quality = element('div', { id: 'quality' });
  ui.collisions = element('div', { id: 'collisions' });
  ui.planSeconds = element('input', { id: 'plan-seconds', type: 'number', value: '5', step: '1', min: '0.1' });
  ui.planEnergy = element('select', { id: 'plan-energy' }, ['contact', 'potential-quality', 'guided-potential-quality', 'autograsp-quality', 'strict-autograsp']
    .map((name) => element('option', { value: name, text: name })));
  ui.planSeed = element('input', { id: 'plan-seed', type: 'number', value: '1', step: '1', min: '0' });
  ui.planTop = element('input', { id: 'plan-top', type: 'number', value: '10', step: '1', min: '1' });
  ui.progress = element('progress', { id: 'plan-progress', max: '1', value: '0' });
  ui.planText = element('span', { id: 'plan-text' });
  ui.graspName = element('span', { id: 'grasp-name', text: 'no grasps' });
  ui.graspFigures = element('div', { id: 'grasp-figures' });
  ui.validation = element('div', { id: 'validation' });
  ui.saveFile = element('input', { id: 'save-file', type: 'text', value: 'edited_world.xml', size: '22' });
  ui.pictureFile = element('input', { id: 'picture-file', type: 'text', value: 'picture.png', size: '22' });
  ui.script = element('textarea', { id: 'script', readonly: 'readonly' });
  const button = (id, text, action) => element('button', { id, text, onclick: action });

  side.append(
    ui.title, message,
    element('h3', { text: 'Hand' }),
    element('div', { class: 'row' }, [
      button('mode-move', 'Move', () => gizmo.setMode('translate')),
      button('mode-turn', 'Turn', () => gizmo.setMode('rotate')),
      element('label', { style: 'display:inline' }, [ui.snap, ' snap 5 mm / 15°'])]),
    element('div', { class: 'row' }, ['mm ', ...ui.position]),
    element('div', { class: 'row' }, ['° ', ...ui.rotation]),
    element('div', { class: 'row' }, [
      button('autograsp', 'Autograsp', () => act('autograsp')),
      button('open', 'Open', () => act('open')),
      button('approach', 'Approach', () => act('approach'))]),
    element('div', { class: 'row' }, [
      button('undo', 'Undo', () => act('undo')),
      button('redo', 'Redo', () => act('redo'))]),
    element('h3', { text: 'DOFs' }), ui.dofs,
    element('h3', { text: 'Eigengrasps' }), ui.eigen,
    element('h3', { text: 'Grasp' }), ui.quality, ui.collisions,
    element('h3', { text: 'Planner' }),
    element('div', { class: 'row' }, ['seconds ', ui.planSeconds, ' ', ui.planEnergy]),
    element('div', { class: 'row' }, ['seed ', ui.planSeed, ' best ', ui.planTop]),
    element('div', { class: 'row' }, [button('plan', 'Plan', startPlan),
      button('plan-stop', 'Stop', () => request('plan_stop').catch((e) => say(e.message, true))),
      ' ', ui.progress]),
    element('div', { class: 'row' }, [ui.planText]),
    element('div', { class: 'row' }, [button('grasp-previous', '←', () => showGrasp(editor.graspIndex - 1)),
      button('grasp-next', '→', () => showGrasp(editor.graspIndex + 1)), ' ', ui.graspName]),
    ui.graspFigures,
    element('div', { class: 'row' }, [button('validate', 'Validate', validate),
      button('play', 'Play', play)]),
    ui.validation,
    element('h3', { text: 'Files' }),
    element('div', { class: 'row' }, [ui.saveFile, button('save', 'Save world', save)]),
    element('div', { class: 'row' }, [ui.pictureFile, button('save-picture', 'Save picture', savePicture)]),
    element('div', { class: 'row' }, [button('copy-lua', 'Copy as Lua', () => copyScript('lua')),
      button('copy-python', 'Copy as Python', () => copyScript('python'))]),
    ui.script);

  // ---- drawing ----
  function draw() {
    const width = canvas.clientWidth, height = canvas.clientHeight;
    if (canvas.width !== width || canvas.height !== height) {
      renderer.setSize(width, height, false);
      camera.aspect = width / height;
      camera.updateProjectionMatrix();
    }
    renderer.render(world, camera);
  }

  function placeNode(node, pose) {
    node.position.fromArray(pose.t);
    node.quaternion.fromArray(pose.q);
  }

  let dragging = false;
  function show(state) {
    editor.state = state;
    for (const [name, pose] of Object.entries(state.bodies)) {
      const node = nodes.get(name);
      if (node) placeNode(node, pose);
    }
    const hand = state.hand;
    if (!dragging) {
      handle.position.fromArray(hand.pose.translation.map((v) => v / 1000));
      const [w, x, y, z] = hand.pose.quaternion;
      handle.quaternion.set(x, y, z, w);
    }
    hand.pose.translation.forEach((v, i) => { ui.position[i].value = v.toFixed(2); });
    const euler = new THREE.Euler().setFromQuaternion(handle.quaternion, 'XYZ');
    [euler.x, euler.y, euler.z].forEach((v, i) => { ui.rotation[i].value = (v * 180 / Math.PI).toFixed(2); });
    syncSliders(ui.dofs, 'dof', hand.dofs.map((d) => ({ value: d.value, min: d.min, max: d.max })), sendDofs);
    syncSliders(ui.eigen, 'eigen', hand.eigengrasps.map((e) => ({ value: e.amplitude, min: e.min, max: e.max })), sendEigen);
    // Collisions: the colliding bodies glow red.
    const colliding = new Set(state.collisions.flat());
    for (const [name, node] of nodes) {
      node.traverse((part) => {
        if (part.material && part.material.emissive) part.material.emissive.setHex(colliding.has(name) ? 0xff0000 : 0x000000);
      });
    }
    ui.collisions.textContent = state.collisions.length
      ? `collisions: ${state.collisions.map((p) => p.join(' / ')).join(', ')}` : 'no collisions';
    ui.collisions.className = state.collisions.length ? 'bad' : 'good';
    const q = state.quality;
    ui.quality.textContent = `epsilon ${format(q.epsilon)} · volume ${format(q.volume)} · ` +
      `force closure ${q.force_closure ? 'yes' : 'no'} · ${q.contacts} contacts`;
    markers.clear();
    for (const contact of state.contacts) markers.add(contactMarker(contact, editor.markerSize));
    document.getElementById('undo').disabled = state.undo === 0;
    document.getElementById('redo').disabled = state.redo === 0;
    draw();
  }

  // One slider and one number per value; rebuilt only when the count changes. A change sends
  // that value with the others as the state has them (not as their sliders round them).
  function syncSliders(box, prefix, values, send) {
    if (box.children.length !== values.length) {
      box.replaceChildren(...values.map((v, i) => {
        const range = element('input', { id: `${prefix}-${i}`, type: 'range', min: String(v.min), max: String(v.max),
          step: String((v.max - v.min) / 500 || 0.001) });
        const typed = element('input', { id: `${prefix}-${i}-value`, type: 'number', step: '0.01' });
        range.addEventListener('input', () => { typed.value = range.value; send(i, Number(range.value), `${prefix}-${i}-${group}`, true); });
        range.addEventListener('change', () => { send(i, Number(range.value), `${prefix}-${i}-${group}`); group += 1; });
        typed.addEventListener('change', () => { range.value = typed.value; send(i, Number(typed.value), ''); });
        return element('div', { class: 'row' }, [`${i} `, range, typed]);
      }));
    }
    values.forEach((v, i) => {
      const range = document.getElementById(`${prefix}-${i}`);
      const typed = document.getElementById(`${prefix}-${i}-value`);
      if (document.activeElement !== range) range.value = String(v.value);
      if (document.activeElement !== typed) typed.value = v.value.toFixed(4);
    });
  }

  // ---- talking to the server ----
  // Moves (drags, sliders) send at most one request at a time; the newest waiting one follows.
  let inFlight = null;
  let waiting = null;
  function sendLatest(action, args) {
    waiting = { action, args };
    if (inFlight) return inFlight;
    const next = async () => {
      while (waiting) {
        const { action: a, args: b } = waiting;
        waiting = null;
        try {
          show(await request(a, b));
          say('');
        } catch (e) {
          say(e.message, true);
        }
      }
      inFlight = null;
    };
    inFlight = next();
    return inFlight;
  }

  async function act(action, args = {}) {
    editor.pending += 1;
    try {
      if (inFlight) await inFlight;
      const answer = await request(action, args);
      if (answer.bodies) show(answer);
      say(answer.ended ? `${action}: ${answer.ended}` : '');
      return answer;
    } catch (e) {
      say(`${action}: ${e.message}`, true);
      throw e;
    } finally {
      editor.pending -= 1;
    }
  }

  let group = 0;
  // While a handle or a slider moves, requests are previews (epsilon by the nearest facet, no
  // volume: fast); the last one, at release, measures as `graspkit grasp` does.
  function sendPose(dragGroup, preview = false) {
    const t = handle.position.toArray().map((v) => v * 1000);
    const q = handle.quaternion;
    return sendLatest('pose', { translation: t, quaternion: [q.w, q.x, q.y, q.z], group: dragGroup, preview });
  }
  function sendDofs(index, value, sliderGroup, preview = false) {
    const values = editor.state.hand.dofs.map((d, i) => (i === index ? value : d.value));
    return sendLatest('dofs', { values, group: sliderGroup, preview });
  }
  function sendEigen(index, value, sliderGroup, preview = false) {
    const amplitudes = editor.state.hand.eigengrasps.map((e, i) => (i === index ? value : e.amplitude));
    return sendLatest('eigengrasps', { amplitudes, group: sliderGroup, preview });
  }
  function typedPose() {
    handle.position.fromArray(ui.position.map((input) => Number(input.value) / 1000));
    const [rx, ry, rz] = ui.rotation.map((input) => Number(input.value) * Math.PI / 180);
    handle.quaternion.setFromEuler(new THREE.Euler(rx, ry, rz, 'XYZ'));
    return sendPose('');
  }
  for (const input of [...ui.position, ...ui.rotation]) input.addEventListener('change', typedPose);

  gizmo.addEventListener('dragging-changed', (event) => {
    orbit.enabled = !event.value;
    dragging = event.value;
    if (event.value) group += 1;
    else sendPose(`drag-${group}`);
  });
  gizmo.addEventListener('objectChange', () => sendPose(`drag-${group}`, true));
  gizmo.addEventListener('change', draw);
  ui.snap.addEventListener('change', () => {
    gizmo.setTranslationSnap(ui.snap.checked ? 0.005 : null);
    gizmo.setRotationSnap(ui.snap.checked ? THREE.MathUtils.degToRad(15) : null);
  });
  orbit.addEventListener('change', draw);
  window.addEventListener('resize', draw);
  window.addEventListener('keydown', (event) => {
    if (event.target.tagName === 'INPUT') return;
    if (event.key === 't') gizmo.setMode('translate');
    if (event.key === 'r') gizmo.setMode('rotate');
    if ((event.ctrlKey || event.metaKey) && event.key === 'z') act(event.shiftKey ? 'redo' : 'undo').catch(() => {});
  });

  // ---- planner, grasps, validation ----
  let planTimer = null;
  async function startPlan() {
    await act('plan', { seconds: Number(ui.planSeconds.value), energy: ui.planEnergy.value,
      seed: Number(ui.planSeed.value), top: Number(ui.planTop.value) });
    editor.planDone = false;
    ui.planText.textContent = 'planning…';
    planTimer = setInterval(pollPlan, 250);
  }
  async function pollPlan() {
    let status;
    try {
      status = await request('plan_status');
    } catch (e) {
      say(e.message, true);
      return;
    }
    ui.progress.value = status.fraction || 0;
    ui.planText.textContent = status.running
      ? `${format(status.seconds, 3)} s, ${status.steps} steps`
      : status.error ? `failed: ${status.error}` : `${status.grasps} grasps in ${format(status.seconds, 3)} s` +
        `${status.stopped ? ' (stopped)' : ''}`;
    if (!status.running) {
      clearInterval(planTimer);
      editor.grasps = (await request('grasps')).grasps;
      editor.planDone = true;
      if (editor.grasps.length) await showGrasp(0);
    }
  }
  async function listGrasps() {
    editor.grasps = (await request('grasps')).grasps;
  }
  async function showGrasp(index) {
    const count = editor.grasps.length;
    if (count === 0) return;
    const wrapped = ((index % count) + count) % count;
    const answer = await act('show_grasp', { index: wrapped });
    editor.graspIndex = wrapped;
    const g = answer.grasp;
    ui.graspName.textContent = `${g.name} (${wrapped + 1} of ${count})`;
    ui.graspFigures.textContent = ['energy', 'epsilon', 'volume', 'contacts']
      .filter((k) => k in g).map((k) => `${k} ${format(g[k])}`).join(' · ');
  }
  async function validate() {
    ui.validation.textContent = 'validating…';
    try {
      const label = await act('validate');
      editor.validation = label;
      ui.validation.textContent = `${label.held ? 'held' : 'not held'}: ` +
        label.directions.map((d) => `${d.direction} ${d.held ? 'ok' : 'lost'}`).join(' ');
    } catch (e) {
      ui.validation.textContent = '';
    }
  }
  // Plays the squeeze under gravity back, frame by frame, then shows the world again.
  async function play() {
    const answer = await act('simulate', { seconds: 1.0 });
    editor.playing = true;
    const frames = answer.frames;
    let index = 0;
    await new Promise((resolve) => {
      const timer = setInterval(() => {
        if (index >= frames.length) {
          clearInterval(timer);
          resolve();
          return;
        }
        for (const [name, pose] of Object.entries(frames[index].bodies)) {
          const node = nodes.get(name);
          if (node) placeNode(node, pose);
        }
        draw();
        index += 1;
      }, 1000 / 30);
    });
    editor.playing = false;
    editor.playedFrames = frames.length;
  }

  // ---- files ----
  async function save() {
    const answer = await act('save', { file: ui.saveFile.value });
    say(`saved ${answer.saved}`);
  }
  function cameraArgs() {
    const target = orbit.target;
    return { position: camera.position.toArray(), target: target.toArray(), up: camera.up.toArray(), fov: camera.fov };
  }
  async function savePicture() {
    const width = canvas.clientWidth, height = canvas.clientHeight;
    const answer = await act('picture', { file: ui.pictureFile.value, width, height, camera: cameraArgs() });
    say(`saved ${answer.saved}`);
  }
  async function copyScript(language) {
    const answer = await act('script', { language });
    ui.script.value = answer.text;
    if (navigator.clipboard) navigator.clipboard.writeText(answer.text).catch(() => {});
  }

  // ---- start ----
  function frame(state) {
    // The camera looks at the object from the side of the hand, at a distance that fits both.
    const box = new THREE.Box3();
    for (const name of [...state.hand.bodies, state.object]) {
      const node = nodes.get(name);
      if (node) box.expandByObject(node);
    }
    const sphere = box.getBoundingSphere(new THREE.Sphere());
    const object = nodes.get(state.object);
    const centre = object ? new THREE.Box3().setFromObject(object).getCenter(new THREE.Vector3()) : sphere.center;
    editor.markerSize = object
      ? 0.25 * new THREE.Box3().setFromObject(object).getBoundingSphere(new THREE.Sphere()).radius : 0.02;
    const direction = new THREE.Vector3(1, -1.2, 0.8).normalize();
    const distance = sphere.radius / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2)) * 1.1;
    camera.up.set(0, 0, 1);
    camera.position.copy(centre).addScaledVector(direction, distance);
    orbit.target.copy(centre);
    orbit.update();
  }

  async function load() {
    const response = await fetch('/api/scene.glb', { headers: { 'X-Graspkit-Token': token } });
    if (!response.ok) throw new Error((await response.json()).error);
    const gltf = await new GLTFLoader().parseAsync(await response.arrayBuffer(), '');
    const scene = gltf.scene;
    scene.traverse((node) => {
      if (node.isMesh) node.material = node.material.clone();  // each body glows on its own
    });
    for (const node of scene.children) nodes.set(node.name, node);
    world.add(scene);
    const state = await request('state');
    ui.title.textContent = `${state.world}: ${state.hand.name}${state.object ? ` and ${state.object}` : " (no object)"}`;
    frame(state);
    show(state);
    if (state.grasps > 0) {
      await listGrasps();
      ui.graspName.textContent = `${editor.grasps.length} grasps`;
    }
  }

  // Where a world point (metres) lands on the canvas, for tests and tools.
  function project(point) {
    const v = new THREE.Vector3(...point).project(camera);
    return [(v.x + 1) / 2 * canvas.clientWidth, (1 - v.y) / 2 * canvas.clientHeight];
  }

  load().then(() => {
    Object.assign(editor, {
      ready: true,
      act,
      request,
      project,
      idle: async () => { while (inFlight || editor.pending) await (inFlight || new Promise((r) => setTimeout(r, 20))); },
      // Moves the handle as a drag of the on-screen handles does: the same requests, one undo step.
      drag: async (translation, quaternion, steps = 5) => {
        const from = handle.position.clone(), to = new THREE.Vector3(...translation.map((v) => v / 1000));
        const q0 = handle.quaternion.clone(), q1 = quaternion ? new THREE.Quaternion(quaternion[1], quaternion[2], quaternion[3], quaternion[0]) : q0;
        gizmo.dispatchEvent({ type: 'dragging-changed', value: true });
        for (let i = 1; i <= steps; ++i) {
          handle.position.lerpVectors(from, to, i / steps);
          handle.quaternion.slerpQuaternions(q0, q1, i / steps);
          gizmo.dispatchEvent({ type: 'objectChange' });
          await inFlight;
        }
        gizmo.dispatchEvent({ type: 'dragging-changed', value: false });
        await inFlight;
      },
    });
    window.graspkitEditor = editor;
  }).catch((e) => {
    say(`cannot load the world: ${e.message}`, true);
    console.error(e);
  });
}

start();

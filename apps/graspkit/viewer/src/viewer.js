// The graspkit view page: the scenes of an embedded binary glTF (one per world or grasp, with
// each grasp's figures and contacts in the scene's extras), shown one at a time with orbit
// controls; with a simulation's frames (view --trajectory), a play button and a time slider. Bundled with three.js into one script at build time; the page needs no network.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

function embedded(id) {
  const element = document.getElementById(id);
  if (!element) throw new Error(`the page has no #${id}`);
  return element.textContent.trim();
}

function base64ToBuffer(text) {
  const bytes = Uint8Array.from(atob(text), (c) => c.charCodeAt(0));
  return bytes.buffer;
}

function formatNumber(value) {
  if (typeof value !== 'number') return String(value);
  return Number.isInteger(value) ? String(value) : value.toPrecision(5);
}

// A contact: a sphere on the object and its friction cone (apex at the point, along the normal).
function contactMarker(contact, size) {
  const group = new THREE.Group();
  const point = new THREE.Vector3(...contact.point);
  const normal = new THREE.Vector3(...contact.normal).normalize();
  // Drawn over everything (no depth test): contacts lie under the fingertips.
  const sphere = new THREE.Mesh(new THREE.SphereGeometry(size * 0.2, 16, 12),
    new THREE.MeshStandardMaterial({ color: 0xd91a1a, depthTest: false }));
  sphere.renderOrder = 2;
  sphere.position.copy(point);
  group.add(sphere);
  const length = size;
  const cone = new THREE.ConeGeometry(length * Math.max(contact.mu, 0.01), length, 24, 1, true);
  cone.translate(0, -length / 2, 0);  // apex at the origin, opening along -y
  const mesh = new THREE.Mesh(cone, new THREE.MeshStandardMaterial({
    color: 0xff5a33, transparent: true, opacity: 0.45, side: THREE.DoubleSide, depthWrite: false,
    depthTest: false,
  }));
  mesh.renderOrder = 1;
  mesh.position.copy(point);
  mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, -1, 0), normal);
  group.add(mesh);
  return group;
}

function start() {
  const meta = JSON.parse(embedded('graspkit-meta'));
  const canvas = document.getElementById('view');
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  const world = new THREE.Scene();
  world.background = new THREE.Color(0xffffff);
  world.add(new THREE.HemisphereLight(0xffffff, 0x666666, 1.6));
  const camera = new THREE.PerspectiveCamera(meta.camera.fov, 1, 0.0005, 1000);
  const headlight = new THREE.DirectionalLight(0xffffff, 1.8);
  headlight.position.set(-0.4, 0.6, 1.0);
  camera.add(headlight);
  world.add(camera);
  const controls = new OrbitControls(camera, canvas);
  camera.position.fromArray(meta.camera.position);
  camera.up.fromArray(meta.camera.up);
  controls.target.fromArray(meta.camera.target);
  controls.update();

  const panel = {
    name: document.getElementById('name'),
    figures: document.getElementById('figures'),
    contacts: document.getElementById('show-contacts'),
  };
  const state = { scenes: [], index: 0, shown: null, markers: null, centre: null };

  function draw() {
    const width = canvas.clientWidth, height = canvas.clientHeight;
    if (canvas.width !== width || canvas.height !== height) {
      renderer.setSize(width, height, false);
      camera.aspect = width / height;
      camera.updateProjectionMatrix();
    }
    renderer.render(world, camera);
  }

  function show(index) {
    if (state.scenes.length === 0) return;
    state.index = ((index % state.scenes.length) + state.scenes.length) % state.scenes.length;
    if (state.shown) world.remove(state.shown);
    if (state.markers) world.remove(state.markers);
    const scene = state.scenes[state.index];
    // Each grasp is framed as the first: the view moves with the scene's centre.
    const centre = scene.userData && scene.userData.centre;
    if (centre && state.centre) {
      const shift = new THREE.Vector3(...centre).sub(new THREE.Vector3(...state.centre));
      controls.target.add(shift);
      camera.position.add(shift);
      controls.update();
    }
    state.centre = centre;
    state.shown = scene;
    world.add(scene);
    const extras = scene.userData || {};
    state.markers = new THREE.Group();
    for (const contact of extras.contacts || [])
      state.markers.add(contactMarker(contact, meta.markerSize));
    state.markers.visible = panel.contacts.checked;
    world.add(state.markers);
    panel.name.textContent = `${extras.name || scene.name || 'scene'} (${state.index + 1} of ${state.scenes.length})`;
    const figures = [];
    for (const key of ['energy', 'epsilon', 'volume', 'contacts', 'force_closure'])
      if (key in (extras.summary || {})) figures.push(`${key} ${formatNumber(extras.summary[key])}`);
    panel.figures.textContent = figures.join(' · ');
    draw();
  }

  // A simulation played back: frame k puts every body where the trajectory had it.
  const frames = meta.trajectory || [];
  const playback = { timer: null, frame: 0 };
  const slider = document.getElementById('time');
  const clock = document.getElementById('clock');
  function seek(k) {
    if (frames.length === 0 || !state.shown) return;
    playback.frame = Math.max(0, Math.min(frames.length - 1, k));
    const poses = frames[playback.frame].bodies;
    state.shown.traverse((node) => {
      const pose = poses[node.name];
      if (!pose || node === state.shown) return;
      node.position.fromArray(pose.t);
      node.quaternion.fromArray(pose.q);
    });
    slider.value = String(playback.frame);
    clock.textContent = `${frames[playback.frame].time.toFixed(3)} s`;
    // Contacts belong to the world as it was loaded, not to a frame of the run.
    if (state.markers) state.markers.visible = playback.frame === 0 && panel.contacts.checked;
    draw();
  }
  function play() {
    if (playback.timer) {
      clearInterval(playback.timer);
      playback.timer = null;
      return;
    }
    if (playback.frame >= frames.length - 1) seek(0);
    playback.timer = setInterval(() => {
      if (playback.frame >= frames.length - 1) {
        clearInterval(playback.timer);
        playback.timer = null;
        return;
      }
      seek(playback.frame + 1);
    }, 1000 / 30);
  }
  if (frames.length > 0) {
    document.getElementById('playback').hidden = false;
    slider.max = String(frames.length - 1);
    slider.addEventListener('input', () => seek(Number(slider.value)));
    document.getElementById('play').addEventListener('click', play);
  }

  // Where a world point (metres) lands on the canvas, for tests and tools.
  function project(point) {
    const v = new THREE.Vector3(...point).project(camera);
    return [(v.x + 1) / 2 * canvas.clientWidth, (1 - v.y) / 2 * canvas.clientHeight];
  }

  document.getElementById('previous').addEventListener('click', () => show(state.index - 1));
  document.getElementById('next').addEventListener('click', () => show(state.index + 1));
  panel.contacts.addEventListener('change', () => {
    if (state.markers) state.markers.visible = panel.contacts.checked;
    draw();
  });
  window.addEventListener('keydown', (event) => {
    if (event.key === 'ArrowRight' || event.key === 'n') show(state.index + 1);
    if (event.key === 'ArrowLeft' || event.key === 'p') show(state.index - 1);
  });
  window.addEventListener('resize', draw);
  controls.addEventListener('change', draw);

  new GLTFLoader().parse(base64ToBuffer(embedded('graspkit-scene')), '', (gltf) => {
    state.scenes = gltf.scenes;
    show(0);
    window.graspkitViewer = {
      ready: true,
      count: state.scenes.length,
      show: (index) => show(index),
      current: () => state.index,
      project,
      frames: frames.length,
      seek,
      // A body's position (metres) as drawn now.
      bodyPosition: (name) => {
        const node = state.shown && state.shown.getObjectByName(name);
        return node ? node.position.toArray() : null;
      },
    };
  }, (error) => {
    panel.name.textContent = `cannot read the scene: ${error.message || error}`;
    console.error(error);
  });
}

start();

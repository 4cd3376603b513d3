// The viewer page: loads the replay the server offers (or ?replay=URL), draws it with three.js
// and plays it. window.tumbleViewer is what the browser test reads and drives; the page sets
// document.body.dataset.state = 'ready' once the first frame is drawn.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { parseReplay, POSE_FLOATS } from './replay.js';
import { ReplayWorld } from './world.js';
import { EnergyPlot } from './plot.js';

const $ = (id) => document.getElementById(id);

function fail(message) {
  $('error').textContent = message;
  $('error').style.display = 'block';
  document.body.dataset.state = 'error';
}

function setUpRenderer(world) {
  const container = $('view');
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio);
  container.appendChild(renderer.domElement);
  const camera = new THREE.PerspectiveCamera(45, 1, 0.01, 1000);
  camera.up.set(0, 0, 1); // Tumble's +Z is up
  const { centre, size } = world.bounds;
  camera.position.copy(centre).add(new THREE.Vector3(0.75 * size, -1.0 * size, 0.6 * size));
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.copy(centre);
  controls.update();
  const resize = () => {
    renderer.setSize(container.clientWidth, container.clientHeight);
    camera.aspect = container.clientWidth / Math.max(container.clientHeight, 1);
    camera.updateProjectionMatrix();
  };
  window.addEventListener('resize', resize);
  resize();
  return { renderer, camera, controls };
}

function addLights(scene) {
  scene.background = new THREE.Color(0x1e2127);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x404040, 1.6));
  const sun = new THREE.DirectionalLight(0xffffff, 1.8);
  sun.position.set(3, -2, 6);
  scene.add(sun);
}

class Player {
  constructor(replay, world, view) {
    Object.assign(this, { replay, world, view, frame: 0, playing: false, selected: -1 });
    this.plot = new EnergyPlot($('energy'), replay.frames);
    this.options = () => ({
      contacts: $('showContacts').checked,
      tension: $('showTension').checked,
      trails: $('showTrails').checked,
      grid: $('showGrid').checked,
    });
    this.#bindControls();
  }

  #bindControls() {
    const last = this.replay.frames.length - 1;
    $('scrub').max = String(last);
    $('scrub').addEventListener('input', () => this.setFrame(Number($('scrub').value)));
    $('play').addEventListener('click', () => this.toggle());
    $('stepBack').addEventListener('click', () => this.setFrame(this.frame - 1));
    $('stepForward').addEventListener('click', () => this.setFrame(this.frame + 1));
    for (const id of ['showContacts', 'showTension', 'showTrails', 'showGrid'])
      $(id).addEventListener('change', () => this.setFrame(this.frame));
    $('legend').style.display = this.replay.description.springs.length ? '' : 'none';
    $('tensionMax').textContent = this.world.tensionMax.toPrecision(3);
    window.addEventListener('keydown', (e) => {
      if (e.key === ' ') this.toggle();
      else if (e.key === 'ArrowLeft') this.setFrame(this.frame - 1);
      else if (e.key === 'ArrowRight') this.setFrame(this.frame + 1);
      else return;
      e.preventDefault();
    });
    this.view.renderer.domElement.addEventListener('pointerdown', (e) => (this.down = [e.clientX, e.clientY]));
    this.view.renderer.domElement.addEventListener('pointerup', (e) => {
      // A click, not the end of an orbit drag.
      if (this.down && Math.hypot(e.clientX - this.down[0], e.clientY - this.down[1]) < 4) this.pick(e);
    });
  }

  toggle() {
    this.playing = !this.playing;
    if (this.playing && this.frame === this.replay.frames.length - 1) this.setFrame(0);
    this.clock = this.replay.frames[this.frame].time;
    $('play').textContent = this.playing ? '⏸' : '▶';
  }

  /// Advances the playback clock by `dt` of wall time (s) times the speed.
  tick(dt) {
    if (!this.playing) return;
    const frames = this.replay.frames;
    this.clock += dt * Number($('speed').value);
    let i = this.frame;
    while (i + 1 < frames.length && frames[i + 1].time <= this.clock) ++i;
    if (i === frames.length - 1 && this.clock > frames[i].time) {
      if ($('loop').checked) {
        this.clock = frames[0].time;
        i = 0;
      } else this.toggle();
    }
    if (i !== this.frame) this.setFrame(i);
  }

  setFrame(index) {
    const frames = this.replay.frames;
    this.frame = Math.min(Math.max(index, 0), frames.length - 1);
    if (!this.playing) this.clock = frames[this.frame].time;
    this.world.show(this.frame, this.options());
    $('scrub').value = String(this.frame);
    $('time').textContent = `t = ${frames[this.frame].time.toFixed(3)} s  (${this.frame + 1}/${frames.length})`;
    this.plot.draw(this.frame);
    this.showInfo();
    this.onChange?.();
  }

  pick(event) {
    const rect = this.view.renderer.domElement.getBoundingClientRect();
    const mouse = new THREE.Vector2(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
    const ray = new THREE.Raycaster();
    ray.setFromCamera(mouse, this.view.camera);
    const hit = ray.intersectObjects(this.world.bodies, true).find((h) => h.object.userData.body !== undefined);
    this.select(hit ? hit.object.userData.body : -1);
  }

  select(body) {
    const previous = this.world.bodies[this.selected];
    previous?.traverse((o) => o.material?.emissive?.setHex(0x000000));
    this.selected = body;
    this.world.bodies[body]?.traverse((o) => o.material?.emissive?.setHex(0x444444));
    this.showInfo();
    this.onChange?.();
  }

  showInfo() {
    const b = this.selected;
    if (b < 0) {
      $('info').textContent = 'click a body';
      return;
    }
    const body = this.replay.description.bodies[b];
    const p = this.replay.frames[this.frame].poses;
    const o = b * POSE_FLOATS;
    const speed = Math.hypot(p[o + 7], p[o + 8], p[o + 9]);
    $('info').textContent = [
      `body ${b}${body.name ? ` (${body.name})` : ''}`,
      `type    ${body.type}`,
      `mass    ${body.mass.toPrecision(4)} kg`,
      `speed   ${speed.toPrecision(4)} m/s`,
      `energy  ${p[o + 10].toPrecision(4)} J (kinetic)`,
      `z       ${p[o + 2].toPrecision(4)} m`,
    ].join('\n');
    $('info').dataset.body = String(b);
  }
}

async function start() {
  const url = new URLSearchParams(location.search).get('replay') ?? 'replay.tumble';
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: ${response.status} ${response.statusText}`);
  const replay = parseReplay(await response.arrayBuffer());
  if (!replay.frames.length) throw new Error('the replay has no frames');
  const scene = new THREE.Scene();
  addLights(scene);
  const world = new ReplayWorld(replay, scene);
  const view = setUpRenderer(world);
  const player = new Player(replay, world, view);
  const title = replay.description.title || 'replay';
  $('title').textContent = `${title}: ${replay.description.bodies.length} bodies, ${replay.description.springs.length} springs, ${replay.frames.length} frames`;
  player.setFrame(0);
  let last = performance.now();
  // Drawn only when something changed: software WebGL (a headless test) stays responsive.
  let dirty = true;
  view.controls.addEventListener('change', () => (dirty = true));
  window.addEventListener('resize', () => (dirty = true));
  player.onChange = () => (dirty = true);
  view.renderer.setAnimationLoop((now) => {
    player.tick((now - last) / 1000);
    last = now;
    if (!dirty) return;
    dirty = false;
    view.renderer.render(scene, view.camera);
  });
  window.tumbleViewer = { replay, world, player, view, scene, THREE };
  document.title = `tumble viewer: ${title}`;
  document.body.dataset.state = 'ready';
}

start().catch((e) => fail(`cannot show the replay: ${e.message}`));

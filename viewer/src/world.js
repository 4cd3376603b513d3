// The three.js scene of a replay: a group per body holding its shapes' meshes, the threads as
// one line set coloured by tension, contacts as points with force arrows, trails, joints and the
// ground grid. Tumble is +Z up; the camera is told so rather than the data being turned.
import * as THREE from 'three';
import { POSE_FLOATS, CONTACT_FLOATS } from './replay.js';

/// The body colour the glTF export uses too: golden-angle hues; static grey, kinematic green.
export function bodyColour(index, type) {
  if (type === 'static') return new THREE.Color(0x8c8c8c);
  if (type === 'kinematic') return new THREE.Color(0x73b273);
  return new THREE.Color().setHSL(((index * 137.508) % 360) / 360, 0.65, 0.6);
}

/// Blue → teal → green → yellow → red for t in [0, 1]: the legend's ramp.
const RAMP = [0x30309a, 0x1f9a8a, 0x9ac030, 0xf0d020, 0xe04020].map((c) => new THREE.Color(c));
export function rampColour(t, out) {
  const x = Math.min(Math.max(t, 0), 1) * (RAMP.length - 1);
  const i = Math.min(Math.floor(x), RAMP.length - 2);
  return out.copy(RAMP[i]).lerp(RAMP[i + 1], x - i);
}

function shapeGeometry(shape) {
  switch (shape.type) {
    case 'box': {
      const [x, y, z] = shape.halfExtents;
      return new THREE.BoxGeometry(2 * x, 2 * y, 2 * z);
    }
    case 'sphere':
      return new THREE.SphereGeometry(shape.radius, 20, 14);
    case 'capsule': // three's capsule and cylinder run along y; Tumble's along z
      return new THREE.CapsuleGeometry(shape.radius, 2 * shape.halfLength, 8, 20).rotateX(Math.PI / 2);
    case 'cylinder':
      return new THREE.CylinderGeometry(shape.radius, shape.radius, 2 * shape.halfLength, 24).rotateX(Math.PI / 2);
    case 'hull': {
      const positions = [];
      for (const face of shape.faces)
        for (let k = 1; k + 1 < face.length; ++k)
          for (const i of [face[0], face[k], face[k + 1]]) positions.push(...shape.vertices[i]);
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
      g.computeVertexNormals();
      return g;
    }
    default:
      return null;
  }
}

function addPlane(group, shape, size) {
  const n = new THREE.Vector3(...shape.normal).normalize();
  const mesh = new THREE.Mesh(
    new THREE.PlaneGeometry(size, size),
    new THREE.MeshStandardMaterial({ color: 0x3a3f47, side: THREE.DoubleSide, transparent: true, opacity: 0.6 }),
  );
  mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), n);
  mesh.position.copy(n).multiplyScalar(shape.offset);
  mesh.userData.plane = true;
  group.add(mesh);
}

export class ReplayWorld {
  constructor(replay, scene) {
    this.replay = replay;
    this.scene = scene;
    const d = replay.description;
    this.bounds = this.#extent();
    this.bodies = d.bodies.map((body, i) => this.#addBody(body, i));
    this.tensionMax = Math.max(1e-9, ...replay.frames.map((f) => f.tensions.reduce((a, b) => Math.max(a, b), 0)));
    this.#addThreads(d.springs);
    this.#addJoints(d.joints);
    this.#addContacts();
    this.#addTrails();
    this.grid = new THREE.GridHelper(this.gridSize, 20, 0x666666, 0x3c3c3c);
    this.grid.rotateX(Math.PI / 2); // into the z = 0 ground plane
    scene.add(this.grid);
  }

  /// Centre and size of everything the first frame shows (bodies' origins), for the camera.
  #extent() {
    const box = new THREE.Box3();
    const p = this.replay.frames[0].poses;
    this.replay.description.bodies.forEach((body, i) => {
      if (body.shapes.some((s) => s.type === 'plane')) return;
      box.expandByPoint(new THREE.Vector3(p[i * POSE_FLOATS], p[i * POSE_FLOATS + 1], p[i * POSE_FLOATS + 2]));
    });
    if (box.isEmpty()) box.set(new THREE.Vector3(-1, -1, 0), new THREE.Vector3(1, 1, 1));
    const size = Math.max(box.getSize(new THREE.Vector3()).length(), 1);
    this.gridSize = Math.ceil(size * 2);
    return { centre: box.getCenter(new THREE.Vector3()), size };
  }

  #addBody(body, index) {
    const group = new THREE.Group();
    group.name = `body ${index}`;
    group.userData = { index };
    const material = new THREE.MeshStandardMaterial({ color: bodyColour(index, body.type), roughness: 0.7 });
    for (const shape of body.shapes) {
      if (shape.type === 'plane') {
        addPlane(group, shape, this.gridSize);
        continue;
      }
      const mesh = new THREE.Mesh(shapeGeometry(shape), material);
      mesh.position.set(...shape.position);
      mesh.quaternion.set(...shape.orientation);
      mesh.userData = { body: index };
      group.add(mesh);
    }
    this.scene.add(group);
    return group;
  }

  #addThreads(springs) {
    this.springs = springs;
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute(new Float32Array(springs.length * 6), 3));
    geometry.setAttribute('color', new THREE.Float32BufferAttribute(new Float32Array(springs.length * 6), 3));
    this.threads = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ vertexColors: true }));
    this.threads.name = 'threads';
    this.threads.frustumCulled = false;
    this.scene.add(this.threads);
  }

  #addJoints(joints) {
    this.joints = joints;
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute(new Float32Array(joints.length * 6), 3));
    this.jointLines = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color: 0xffffff }));
    this.jointLines.frustumCulled = false;
    this.scene.add(this.jointLines);
  }

  #addContacts() {
    const most = Math.max(1, ...this.replay.frames.map((f) => f.contactCount));
    this.forceMax = Math.max(1e-9, ...this.replay.frames.map((f) => {
      let m = 0;
      for (let k = 6; k < f.contacts.length; k += CONTACT_FLOATS) m = Math.max(m, f.contacts[k]);
      return m;
    }));
    const points = new THREE.BufferGeometry();
    points.setAttribute('position', new THREE.Float32BufferAttribute(new Float32Array(most * 3), 3));
    const arrows = new THREE.BufferGeometry();
    arrows.setAttribute('position', new THREE.Float32BufferAttribute(new Float32Array(most * 6), 3));
    this.contactPoints = new THREE.Points(points, new THREE.PointsMaterial({ color: 0xff3030, size: 5, sizeAttenuation: false }));
    this.contactArrows = new THREE.LineSegments(arrows, new THREE.LineBasicMaterial({ color: 0xff8080 }));
    for (const o of [this.contactPoints, this.contactArrows]) {
      o.frustumCulled = false;
      o.visible = false;
      this.scene.add(o);
    }
  }

  /// Trails of up to 64 dynamic bodies (every k-th of a net), from the first frame to now.
  #addTrails() {
    const dynamic = this.replay.description.bodies.flatMap((b, i) => (b.type === 'dynamic' ? [i] : []));
    const stride = Math.ceil(dynamic.length / 64);
    this.trailBodies = dynamic.filter((_, k) => k % stride === 0);
    const n = this.replay.frames.length;
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute(new Float32Array(this.trailBodies.length * n * 6), 3));
    this.trails = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color: 0xaaaaaa, transparent: true, opacity: 0.6 }));
    this.trails.frustumCulled = false;
    this.trails.visible = false;
    this.scene.add(this.trails);
  }

  /// World point of a body-frame point at frame f (into `out`).
  #worldPoint(f, body, local, out) {
    if (body < 0) return out.set(...local);
    const p = f.poses;
    const o = body * POSE_FLOATS;
    const q = new THREE.Quaternion(p[o + 3], p[o + 4], p[o + 5], p[o + 6]);
    return out.set(...local).applyQuaternion(q).add(new THREE.Vector3(p[o], p[o + 1], p[o + 2]));
  }

  /// Shows frame `index`: poses, thread ends and colours, joints, contacts, trails.
  show(index, options) {
    const f = this.replay.frames[index];
    const p = f.poses;
    this.bodies.forEach((g, i) => {
      const o = i * POSE_FLOATS;
      g.position.set(p[o], p[o + 1], p[o + 2]);
      g.quaternion.set(p[o + 3], p[o + 4], p[o + 5], p[o + 6]);
    });
    const v = new THREE.Vector3();
    const colour = new THREE.Color();
    const pos = this.threads.geometry.attributes.position;
    const col = this.threads.geometry.attributes.color;
    this.springs.forEach((s, k) => {
      pos.setXYZ(2 * k, ...this.#worldPoint(f, s.bodyA, s.anchorA, v).toArray());
      pos.setXYZ(2 * k + 1, ...this.#worldPoint(f, s.bodyB, s.anchorB, v).toArray());
      if (options.tension && f.tensions.length) rampColour(f.tensions[k] / this.tensionMax, colour);
      else colour.set(0xd0b040);
      col.setXYZ(2 * k, colour.r, colour.g, colour.b);
      col.setXYZ(2 * k + 1, colour.r, colour.g, colour.b);
    });
    pos.needsUpdate = col.needsUpdate = true;
    const jp = this.jointLines.geometry.attributes.position;
    this.joints.forEach((j, k) => {
      jp.setXYZ(2 * k, ...this.#worldPoint(f, j.bodyA, j.anchorA, v).toArray());
      jp.setXYZ(2 * k + 1, ...this.#worldPoint(f, j.bodyB, j.anchorB, v).toArray());
    });
    jp.needsUpdate = true;
    this.#showContacts(f, options.contacts);
    this.#showTrails(index, options.trails);
    this.grid.visible = options.grid;
  }

  #showContacts(f, visible) {
    this.contactPoints.visible = this.contactArrows.visible = visible;
    if (!visible) return;
    const c = f.contacts;
    const pts = this.contactPoints.geometry.attributes.position;
    const arr = this.contactArrows.geometry.attributes.position;
    const scale = (0.15 * this.bounds.size) / this.forceMax; // the largest force: 15 % of the scene
    for (let k = 0; k < f.contactCount; ++k) {
      const o = k * CONTACT_FLOATS;
      const len = c[o + 6] * scale;
      pts.setXYZ(k, c[o], c[o + 1], c[o + 2]);
      arr.setXYZ(2 * k, c[o], c[o + 1], c[o + 2]);
      arr.setXYZ(2 * k + 1, c[o] + len * c[o + 3], c[o + 1] + len * c[o + 4], c[o + 2] + len * c[o + 5]);
    }
    this.contactPoints.geometry.setDrawRange(0, f.contactCount);
    this.contactArrows.geometry.setDrawRange(0, 2 * f.contactCount);
    pts.needsUpdate = arr.needsUpdate = true;
  }

  #showTrails(index, visible) {
    this.trails.visible = visible;
    if (!visible) return;
    const a = this.trails.geometry.attributes.position;
    let n = 0;
    for (const b of this.trailBodies) {
      for (let i = 1; i <= index; ++i) {
        const p0 = this.replay.frames[i - 1].poses;
        const p1 = this.replay.frames[i].poses;
        const o = b * POSE_FLOATS;
        a.setXYZ(n++, p0[o], p0[o + 1], p0[o + 2]);
        a.setXYZ(n++, p1[o], p1[o + 1], p1[o + 2]);
      }
    }
    this.trails.geometry.setDrawRange(0, n);
    a.needsUpdate = true;
  }
}

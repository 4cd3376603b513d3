// Reads a Tumble replay file (docs/replay.md, version 1): the JSON description and the frames,
// as typed-array views into the file's bytes (no copies).

const MAGIC = 'TUMBLERP';
const FRAME_TAG = 0x4d415246;
const END_TAG = 0x21444e45;
export const POSE_FLOATS = 11; // position 3, quaternion x y z w, velocity 3, kinetic energy
export const CONTACT_FLOATS = 7; // point 3, normal 3, normal force

export function parseReplay(buffer) {
  const view = new DataView(buffer);
  const text = new TextDecoder();
  if (buffer.byteLength < 16 || text.decode(new Uint8Array(buffer, 0, 8)) !== MAGIC)
    throw new Error('not a Tumble replay file');
  const version = view.getUint32(8, true);
  if (version !== 1) throw new Error(`replay version ${version} is not supported (this viewer reads 1)`);
  const length = view.getUint32(12, true);
  const description = JSON.parse(text.decode(new Uint8Array(buffer, 16, length)));
  const bodies = description.bodies.length;
  const springs = description.frame.tensions ? description.springs.length : 0;
  const frames = [];
  let at = 16 + length;
  const need = (bytes) => {
    if (at + bytes > buffer.byteLength) throw new Error(`truncated replay at byte ${at}`);
  };
  for (;;) {
    need(4);
    const tag = view.getUint32(at, true);
    at += 4;
    if (tag === END_TAG) break;
    if (tag !== FRAME_TAG) throw new Error(`byte ${at - 4} holds neither a frame nor the end`);
    need(24);
    const time = view.getFloat64(at, true);
    const energy = new Float32Array(buffer, at + 8, 3);
    const contactCount = view.getUint32(at + 20, true);
    at += 24;
    need(4 * (bodies * POSE_FLOATS + springs + contactCount * CONTACT_FLOATS));
    const poses = new Float32Array(buffer, at, bodies * POSE_FLOATS);
    at += poses.byteLength;
    const tensions = new Float32Array(buffer, at, springs);
    at += tensions.byteLength;
    const contacts = new Float32Array(buffer, at, contactCount * CONTACT_FLOATS);
    at += contacts.byteLength;
    frames.push({ time, energy, poses, tensions, contacts, contactCount });
  }
  return { version, description, frames };
}

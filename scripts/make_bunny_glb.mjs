// Converts the Stanford bunny of the npm package `bunny` (1.0.1) into assets/bunny.glb.
//
//   tmp=$(mktemp -d) && (cd "$tmp" && npm pack bunny@1.0.1 && tar xzf bunny-1.0.1.tgz)
//   node scripts/make_bunny_glb.mjs "$tmp/package" assets/bunny.glb
//
// The output is deterministic: the same package gives the same bytes. The script refuses
// any index.js other than the one recorded below, so the GLB cannot drift from its source.
//
// What it does (assets/README.md explains why):
//   - scales the scan (y up, 9.658 units tall) to a 150 mm figurine, in metres (glTF);
//   - puts the base on y = 0 and centres the bounding box in x and z;
//   - computes area-weighted vertex normals (the package has none), CCW winding kept;
//   - writes one primitive: POSITION, NORMAL (float32), uint16 indices;
//   - one material whose extras.sss names the measured preset skin1 (Jensen et al. 2001).
import { createHash } from 'node:crypto';
import { readFileSync, writeFileSync, renameSync } from 'node:fs';
import { createRequire } from 'node:module';
import { resolve } from 'node:path';

const SOURCE_SHA256 = '4c428649f2cabf3c11a0225f58367c503d181b7e2a59223a610c88a5308412b3';
const HEIGHT_M = 0.150;

if (process.argv.length !== 4) {
  console.error('usage: node scripts/make_bunny_glb.mjs BUNNY_PACKAGE_DIR OUT.glb');
  process.exit(2);
}
const pkgDir = resolve(process.argv[2]);
const outPath = resolve(process.argv[3]);
const indexJs = readFileSync(`${pkgDir}/index.js`);
const sha = createHash('sha256').update(indexJs).digest('hex');
if (sha !== SOURCE_SHA256) {
  console.error(`${pkgDir}/index.js: sha256 ${sha}, expected ${SOURCE_SHA256} (bunny@1.0.1)`);
  process.exit(2);
}
const pkg = JSON.parse(readFileSync(`${pkgDir}/package.json`, 'utf8'));
const { positions, cells } = createRequire(import.meta.url)(`${pkgDir}/index.js`);

// Bounding box of the scan, then metres with the base on y = 0.
const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
for (const p of positions)
  for (let i = 0; i < 3; ++i) { lo[i] = Math.min(lo[i], p[i]); hi[i] = Math.max(hi[i], p[i]); }
const scale = HEIGHT_M / (hi[1] - lo[1]);
const offset = [-(lo[0] + hi[0]) / 2, -lo[1], -(lo[2] + hi[2]) / 2];
const n = positions.length;
const pos = new Float32Array(3 * n);
positions.forEach((p, v) => { for (let i = 0; i < 3; ++i) pos[3 * v + i] = (p[i] + offset[i]) * scale; });

// Area-weighted normals: the sum of the unnormalised face normals around each vertex.
const acc = new Float64Array(3 * n);
for (const [a, b, c] of cells) {
  const e1 = [0, 1, 2].map(i => pos[3 * b + i] - pos[3 * a + i]);
  const e2 = [0, 1, 2].map(i => pos[3 * c + i] - pos[3 * a + i]);
  const f = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
  for (const v of [a, b, c]) for (let i = 0; i < 3; ++i) acc[3 * v + i] += f[i];
}
const nrm = new Float32Array(3 * n);
for (let v = 0; v < n; ++v) {
  const l = Math.hypot(acc[3 * v], acc[3 * v + 1], acc[3 * v + 2]);
  if (!(l > 0)) throw new Error(`vertex ${v} has no area around it`);
  for (let i = 0; i < 3; ++i) nrm[3 * v + i] = acc[3 * v + i] / l;
}
if (n > 65535) throw new Error('too many vertices for uint16 indices');
const idx = new Uint16Array(3 * cells.length);
cells.forEach((t, k) => { for (let i = 0; i < 3; ++i) idx[3 * k + i] = t[i]; });

// Binary buffer: positions | normals | indices, each 4-byte aligned.
const pad4 = x => (x + 3) & ~3;
const views = [pos, nrm, idx].map(a => Buffer.from(a.buffer, a.byteOffset, a.byteLength));
let offsetBytes = 0;
const bufferViews = views.map((v, i) => {
  const view = { buffer: 0, byteOffset: offsetBytes, byteLength: v.length, target: i < 2 ? 34962 : 34963 };
  offsetBytes = pad4(offsetBytes + v.length);
  return view;
});
const bin = Buffer.alloc(offsetBytes);
views.forEach((v, i) => v.copy(bin, bufferViews[i].byteOffset));
const minmax = a => {
  const mn = [Infinity, Infinity, Infinity], mx = [-Infinity, -Infinity, -Infinity];
  for (let v = 0; v < a.length / 3; ++v)
    for (let i = 0; i < 3; ++i) { mn[i] = Math.min(mn[i], a[3 * v + i]); mx[i] = Math.max(mx[i], a[3 * v + i]); }
  return { min: mn, max: mx };
};

const gltf = {
  asset: {
    version: '2.0',
    generator: 'sss-viewer scripts/make_bunny_glb.mjs',
    copyright: 'Stanford bunny: Stanford 3D Scanning Repository, Stanford Computer Graphics Laboratory',
    extras: {
      source: `npm ${pkg.name}@${pkg.version} index.js`,
      source_sha256: SOURCE_SHA256,
      metres_per_source_unit: scale,
    },
  },
  scene: 0,
  scenes: [{ name: 'bunny', nodes: [0] }],
  nodes: [{ name: 'bunny', mesh: 0 }],
  meshes: [{ name: 'bunny', primitives: [{ attributes: { POSITION: 0, NORMAL: 1 }, indices: 2, material: 0, mode: 4 }] }],
  materials: [{
    name: 'skin1',
    pbrMetallicRoughness: { baseColorFactor: [1, 1, 1, 1], metallicFactor: 0, roughnessFactor: 0.45 },
    extras: { sss: { preset: 'skin1', gaussians: 6 } },
  }],
  buffers: [{ byteLength: bin.length }],
  bufferViews,
  accessors: [
    { bufferView: 0, componentType: 5126, count: n, type: 'VEC3', ...minmax(pos) },
    { bufferView: 1, componentType: 5126, count: n, type: 'VEC3' },
    { bufferView: 2, componentType: 5123, count: idx.length, type: 'SCALAR' },
  ],
};

// GLB: 12-byte header, JSON chunk padded with spaces, BIN chunk padded with zeros.
let json = Buffer.from(JSON.stringify(gltf), 'utf8');
json = Buffer.concat([json, Buffer.alloc(pad4(json.length) - json.length, 0x20)]);
const chunk = (type, data) => {
  const h = Buffer.alloc(8);
  h.writeUInt32LE(data.length, 0);
  h.writeUInt32LE(type, 4);
  return Buffer.concat([h, data]);
};
const body = Buffer.concat([chunk(0x4e4f534a, json), chunk(0x004e4942, bin)]);
const header = Buffer.alloc(12);
header.write('glTF', 0, 'ascii');
header.writeUInt32LE(2, 4);
header.writeUInt32LE(12 + body.length, 8);
const tmp = `${outPath}.tmp-${process.pid}`;
writeFileSync(tmp, Buffer.concat([header, body]));
renameSync(tmp, outPath);
console.log(`${outPath}: ${n} vertices, ${cells.length} triangles, ${(hi[1] - lo[1]) * scale} m tall`);

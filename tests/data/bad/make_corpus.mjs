// Writes the malformed-glTF corpus of tests/data/bad/ (issue 7): one file per failure
// class, each a small mutation of one valid triangle, and expected.json, which names
// for every file the object/field the error must mention and a phrase of its message.
// tests/scene/test_bad_corpus.cpp loads each file and checks both.
//
//   node tests/data/bad/make_corpus.mjs            (rewrites the folder's files)
//
// The output is deterministic; the files are committed so that tests and fuzzers can
// use them without node.
import { writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const dir = dirname(fileURLToPath(import.meta.url));
const expected = {};

// One triangle: positions (36 bytes) | normals (36 bytes) | uint16 indices (6 + 2 pad).
function triangleBin({ nanPosition = false, index2 = 2 } = {}) {
  const b = Buffer.alloc(80);
  const pos = [0, 0, 0, 1, 0, 0, 0, 1, 0];
  pos.forEach((v, i) => b.writeFloatLE(v, 4 * i));
  if (nanPosition) b.writeUInt32LE(0x7fc00000, 4 * 4);  // vertex 1, y = NaN
  for (let v = 0; v < 3; ++v) b.writeFloatLE(1, 36 + 12 * v + 8);  // normal +z
  b.writeUInt16LE(0, 72); b.writeUInt16LE(1, 74); b.writeUInt16LE(index2, 76);
  return b;
}

function base(bin = triangleBin()) {
  return {
    asset: { version: '2.0', generator: 'tests/data/bad/make_corpus.mjs' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0 }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0, NORMAL: 1 }, indices: 2, material: 0 }] }],
    materials: [{ name: 'skin', extras: { sss: { preset: 'skin1' } } }],
    buffers: [{ byteLength: bin.length, uri: 'data:application/octet-stream;base64,' + bin.toString('base64') }],
    bufferViews: [
      { buffer: 0, byteOffset: 0, byteLength: 72, byteStride: 12 },
      { buffer: 0, byteOffset: 72, byteLength: 6 },
    ],
    accessors: [
      { bufferView: 0, byteOffset: 0, componentType: 5126, count: 3, type: 'VEC3' },
      { bufferView: 0, byteOffset: 36, componentType: 5126, count: 3, type: 'VEC3' },
      { bufferView: 1, componentType: 5123, count: 3, type: 'SCALAR' },
    ],
  };
}

function gltf(name, where, phrase, mutate, bin) {
  const doc = base(bin);
  if (mutate) mutate(doc);
  writeFileSync(join(dir, name), JSON.stringify(doc, null, 1) + '\n');
  expected[name] = { where, phrase };
}

function glbBytes(doc, bin) {
  const pad = (buf, fill) => Buffer.concat([buf, Buffer.alloc((4 - (buf.length % 4)) % 4, fill)]);
  const json = pad(Buffer.from(JSON.stringify(doc)), 0x20);
  const binp = pad(bin, 0);
  const chunk = (type, data) => {
    const h = Buffer.alloc(8); h.writeUInt32LE(data.length, 0); h.writeUInt32LE(type, 4);
    return Buffer.concat([h, data]);
  };
  const body = Buffer.concat([chunk(0x4e4f534a, json), chunk(0x004e4942, binp)]);
  const header = Buffer.alloc(12);
  header.write('glTF', 0); header.writeUInt32LE(2, 4); header.writeUInt32LE(12 + body.length, 8);
  return Buffer.concat([header, body]);
}

function glb(name, where, phrase, mutateBytes) {
  const bin = triangleBin();
  const doc = base(bin);
  delete doc.buffers[0].uri;
  const bytes = glbBytes(doc, bin);
  writeFileSync(join(dir, name), mutateBytes(bytes));
  expected[name] = { where, phrase };
}

// The container.
glb('glb_bad_magic.glb', 'glb.header.magic', 'glTF', b => { b.write('glTX', 0); return b; });
glb('glb_version_1.glb', 'glb.header.version', 'must be 2', b => { b.writeUInt32LE(1, 4); return b; });
glb('glb_truncated.glb', 'glb.header.length', 'truncated', b => b.subarray(0, b.length >> 1));
glb('glb_json_chunk_overflow.glb', 'glb.chunks[0].chunkLength', 'past the end', b => { b.writeUInt32LE(0xfffffff0, 12); return b; });
glb('glb_bin_chunk_overflow.glb', 'glb.chunks[1].chunkLength', 'past the end', b => {
  const at = 20 + b.readUInt32LE(12); b.writeUInt32LE(b.readUInt32LE(at) + 64, at); return b;
});
glb('glb_json_not_first.glb', 'glb.chunks[0].chunkType', 'JSON', b => { b.writeUInt32LE(0x004e4942, 16); return b; });
// JSON itself.
writeFileSync(join(dir, 'not_json.gltf'), '{"asset": {"version": "2.0"}, "nodes": [ }\n');
expected['not_json.gltf'] = { where: 'not_json.gltf', phrase: 'not valid JSON' };
gltf('json_too_deep.gltf', 'json_too_deep.gltf', 'nests deeper', d => {
  let x = {}; for (let i = 0; i < 100; ++i) x = { a: x }; d.nodes[0].extras = x;
});
gltf('required_extension.gltf', 'extensionsRequired[0]', 'not supported', d => {
  d.extensionsUsed = d.extensionsRequired = ['KHR_draco_mesh_compression'];
});
// URIs.
gltf('uri_absolute.gltf', 'buffers[0].uri', 'absolute path', d => { d.buffers[0].uri = '/etc/passwd'; });
gltf('uri_dotdot.gltf', 'buffers[0].uri', '".." segment', d => { d.buffers[0].uri = '../secret.bin'; });
gltf('uri_percent_dotdot.gltf', 'buffers[0].uri', 'percent-decoded', d => { d.buffers[0].uri = '%2e%2e/secret.bin'; });
gltf('uri_http.gltf', 'buffers[0].uri', 'scheme', d => { d.buffers[0].uri = 'http://example.com/triangle.bin'; });
gltf('uri_file_scheme.gltf', 'buffers[0].uri', 'scheme', d => { d.buffers[0].uri = 'file:///etc/passwd'; });
gltf('uri_bad_base64.gltf', 'buffers[0].uri', 'base64', d => { d.buffers[0].uri = d.buffers[0].uri.slice(0, -8) + 'AB$D!!==' ; });
gltf('uri_base64_wrong_length.gltf', 'buffers[0].uri', 'byteLength', d => { d.buffers[0].byteLength = 84; });
gltf('uri_wrong_media_type.gltf', 'buffers[0].uri', 'type', d => { d.buffers[0].uri = d.buffers[0].uri.replace('application/octet-stream', 'text/html'); });
// Indices and byte ranges.
gltf('view_past_buffer.gltf', 'bufferViews[1].byteLength', 'run past', d => { d.bufferViews[1].byteLength = 64; });
gltf('view_bad_buffer_index.gltf', 'bufferViews[0].buffer', 'does not exist', d => { d.bufferViews[0].buffer = 3; });
gltf('accessor_count_past_view.gltf', 'accessors[0].count', 'run past', d => { d.accessors[0].count = 7; });
gltf('accessor_stride_past_view.gltf', 'accessors[1].count', 'stride 24', d => { d.bufferViews[0].byteStride = 24; });
gltf('view_stride_invalid.gltf', 'bufferViews[0].byteStride', '[4, 252]', d => { d.bufferViews[0].byteStride = 256; });
gltf('accessor_huge_count.gltf', 'accessors[0].count', 'run past', d => { d.accessors[0].count = 2 ** 62; });
gltf('accessor_misaligned.gltf', 'accessors[0].byteOffset', 'aligned', d => { d.accessors[0].byteOffset = 2; d.accessors[0].count = 1; });
gltf('accessor_sparse.gltf', 'accessors[0].sparse', 'not supported', d => {
  d.accessors[0].sparse = { count: 1, indices: { bufferView: 1, componentType: 5123 }, values: { bufferView: 0 } };
});
gltf('accessor_index_missing.gltf', 'meshes[0].primitives[0].attributes.POSITION', 'accessors[9] does not exist', d => {
  d.meshes[0].primitives[0].attributes.POSITION = 9;
});
gltf('position_not_vec3.gltf', 'accessors[0].type', 'component', d => { d.accessors[0].type = 'VEC2'; });
gltf('position_not_float.gltf', 'accessors[0].componentType', 'FLOAT', d => { d.accessors[0].componentType = 5122; });
gltf('attribute_counts_differ.gltf', 'attributes.NORMAL', 'POSITION has 3', d => { d.accessors[1].count = 2; });
gltf('index_out_of_range.gltf', 'meshes[0].primitives[0].indices', 'only 3 vertices', null, triangleBin({ index2: 7 }));
gltf('indices_not_whole_triangles.gltf', 'meshes[0].primitives[0].indices', 'whole triangles', d => { d.accessors[2].count = 2; });
gltf('indices_float.gltf', 'accessors[2].componentType', 'UNSIGNED', d => { d.accessors[2].componentType = 5126; d.accessors[2].count = 1; });
gltf('primitive_mode_invalid.gltf', 'meshes[0].primitives[0].mode', 'not a glTF primitive mode', d => { d.meshes[0].primitives[0].mode = 9; });
gltf('material_index_missing.gltf', 'meshes[0].primitives[0].material', 'materials[4] does not exist', d => { d.meshes[0].primitives[0].material = 4; });
gltf('mesh_index_missing.gltf', 'nodes[0].mesh', 'meshes[2] does not exist', d => { d.nodes[0].mesh = 2; });
// Values.
gltf('position_nan.gltf', 'meshes[0].primitives[0].attributes.POSITION', 'nan', null, triangleBin({ nanPosition: true }));
gltf('matrix_not_float.gltf', 'nodes[0].matrix[12]', 'fits a float', d => {
  d.nodes[0].matrix = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1e39, 0, 0, 1];
});
gltf('rotation_zero.gltf', 'nodes[0].rotation', 'zero quaternion', d => { d.nodes[0].rotation = [0, 0, 0, 0]; });
gltf('base_color_out_of_range.gltf', 'materials[0].pbrMetallicRoughness.baseColorFactor[1]', '[0, 1]', d => {
  d.materials[0].pbrMetallicRoughness = { baseColorFactor: [1, 2, 1, 1] };
});
gltf('camera_yfov_zero.gltf', 'cameras[0].perspective.yfov', '(0, pi)', d => {
  d.cameras = [{ type: 'perspective', perspective: { yfov: 0, znear: 0.1 } }]; d.nodes[0].camera = 0;
});
gltf('light_spot_cone.gltf', 'spot.outerConeAngle', '(0, pi/2]', d => {
  d.extensionsUsed = ['KHR_lights_punctual'];
  d.extensions = { KHR_lights_punctual: { lights: [{ type: 'spot', spot: { innerConeAngle: 0.1, outerConeAngle: 3 } }] } };
  d.nodes[0].extensions = { KHR_lights_punctual: { light: 0 } };
});
// The graph.
gltf('node_cycle.gltf', 'children', 'cycle', d => {
  d.nodes = [{ mesh: 0 }, { children: [2] }, { children: [1] }];
});
gltf('node_own_child.gltf', 'nodes[0].children[0]', 'itself', d => { d.nodes[0].children = [0]; });
gltf('node_two_parents.gltf', 'nodes[1].children[0]', 'only one parent', d => {
  d.nodes = [{ children: [2] }, { children: [2] }, { mesh: 0 }]; d.scenes[0].nodes = [0, 1];
});
gltf('scene_root_is_child.gltf', 'scenes[0].nodes[1]', 'not a root', d => {
  d.nodes = [{ children: [1] }, { mesh: 0 }]; d.scenes[0].nodes = [0, 1];
});
gltf('node_child_missing.gltf', 'nodes[0].children[0]', 'nodes[5] does not exist', d => { d.nodes[0].children = [5]; });
// Images.
gltf('image_view_past_buffer.gltf', 'bufferViews[2].byteLength', 'buffers[0]', d => {
  d.bufferViews.push({ buffer: 0, byteOffset: 60, byteLength: 40 });
  d.images = [{ bufferView: 2, mimeType: 'image/png' }];
});
gltf('image_not_png.gltf', 'images[0].uri', 'neither PNG nor JPEG', d => {
  d.images = [{ uri: 'data:image/png;base64,' + Buffer.from('GIF89a not really').toString('base64') }];
  d.textures = [{ source: 0 }];
  d.materials[0].pbrMetallicRoughness = { baseColorTexture: { index: 0 } };
});
// materials[i].extras.sss.
const sss = (name, where, phrase, block) => gltf(name, 'materials[0].extras.sss' + where, phrase, d => { d.materials[0].extras.sss = block; });
sss('sss_sigma_a_negative.gltf', '.sigma_a[1]', 'must be >= 0 mm^-1, got -1', { sigma_a: [0.1, -1, 0.1], sigma_s: [1, 1, 1] });
sss('sss_sigma_s_negative.gltf', '.sigma_s', 'must be >= 0 mm^-1', { sigma_a: 0.1, sigma_s: -2 });
sss('sss_eta_zero.gltf', '.eta', 'must be > 0, got 0', { sigma_a: 0.1, sigma_s: 1, eta: 0 });
sss('sss_g_one.gltf', '.g', '(-1, 1), got 1', { sigma_a: 0.1, sigma_s: 1, g: 1 });
sss('sss_unknown_preset.gltf', '.preset', 'unknown preset "jade"', { preset: 'jade' });
sss('sss_preset_spectralon.gltf', '.preset', 'cannot be rendered', { preset: 'spectralon' });
sss('sss_gaussians_nine.gltf', '.gaussians', '[1, 8], got 9', { preset: 'skin1', gaussians: 9 });
sss('sss_color_above_one.gltf', '.color[0]', 'between 0 and 1, got 1.2', { color: [1.2, 0.5, 0.5], mfp: [1, 1, 1] });
sss('sss_mfp_zero.gltf', '.mfp[2]', '> 0 mm, got 0', { color: [0.5, 0.5, 0.5], mfp: [1, 1, 0] });
sss('sss_unknown_model.gltf', '.model', 'unknown model', { preset: 'skin1', model: 'quadpole' });
sss('sss_scale_zero.gltf', '.scale', '> 0', { preset: 'skin1', scale: 0 });
sss('sss_unknown_field.gltf', '.sigmaa', 'unknown field', { sigmaa: [1, 1, 1] });
sss('sss_two_sources.gltf', '', 'only one', { preset: 'skin1', sigma_a: 1, sigma_s: 1 });
sss('sss_albedo_mode.gltf', '.albedo_mode', 'post-scatter', { preset: 'skin1', albedo_mode: 'before' });

writeFileSync(join(dir, 'expected.json'), JSON.stringify(expected, null, 1) + '\n');
console.log(`${Object.keys(expected).length} files`);

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
import { deflateSync } from 'node:zlib';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const dir = dirname(fileURLToPath(import.meta.url));
const expected = {};

// One triangle: positions (36 bytes) | normals (36 bytes) | uint16 indices (6 + 2 pad).
function triangleBin({ nanPosition = false, infPosition = false, nanNormal = false, index2 = 2 } = {}) {
  const b = Buffer.alloc(80);
  const pos = [0, 0, 0, 1, 0, 0, 0, 1, 0];
  pos.forEach((v, i) => b.writeFloatLE(v, 4 * i));
  if (nanPosition) b.writeUInt32LE(0x7fc00000, 4 * 4);  // vertex 1, y = NaN
  if (infPosition) b.writeUInt32LE(0x7f800000, 4 * 6);  // vertex 2, x = +Inf
  for (let v = 0; v < 3; ++v) b.writeFloatLE(1, 36 + 12 * v + 8);  // normal +z
  if (nanNormal) b.writeUInt32LE(0xffc00000, 36 + 12 + 4);  // normal 1, y = -NaN
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

function gltf(name, where, phrase, mutate, bin, editText) {
  const doc = base(bin);
  if (mutate) mutate(doc);
  let text = JSON.stringify(doc, null, 1) + '\n';
  if (editText) text = editText(text);  // what JSON.stringify cannot write (2^64 - 16, 1e400)
  writeFileSync(join(dir, name), text);
  expected[name] = { where, phrase };
}

// A raw-text edit that must change something.
const replaceOnce = (from, to) => text => {
  if (!text.includes(from)) throw new Error('make_corpus: ' + from + ' not found');
  return text.replace(from, to);
};

// CRC-32 of PNG chunks (ISO 3309 / PNG spec §5.5: polynomial 0xEDB88320, reflected).
function crc32(buf) {
  let c = 0xffffffff;
  for (const byte of buf) {
    c ^= byte;
    for (let k = 0; k < 8; ++k) c = (c >>> 1) ^ (0xedb88320 & -(c & 1));
  }
  return (c ^ 0xffffffff) >>> 0;
}
function pngChunk(type, data) {
  const head = Buffer.alloc(8); head.writeUInt32BE(data.length, 0); head.write(type, 4, 'latin1');
  const crc = Buffer.alloc(4); crc.writeUInt32BE(crc32(Buffer.concat([head.subarray(4), data])), 0);
  return Buffer.concat([head, data, crc]);
}
// An 8-bit RGBA PNG of w x h; `idat` false leaves out the pixel data (header only).
function png(w, h, { idat = true } = {}) {
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(w, 0); ihdr.writeUInt32BE(h, 4); ihdr[8] = 8; ihdr[9] = 6;  // depth 8, RGBA
  const rows = () => {
    const r = Buffer.alloc(h * (1 + 4 * w), 0x80);
    for (let y = 0; y < h; ++y) r[y * (1 + 4 * w)] = 0;  // filter type 0
    return r;
  };
  return Buffer.concat([Buffer.from('\x89PNG\r\n\x1a\n', 'latin1'), pngChunk('IHDR', ihdr),
    ...(idat ? [pngChunk('IDAT', deflateSync(rows()))] : []), pngChunk('IEND', Buffer.alloc(0))]);
}
const dataUri = (type, bytes) => 'data:' + type + ';base64,' + bytes.toString('base64');
// The material samples textures[0] (images[0], made by `image`) as its base colour.
const textured = image => d => {
  d.images = [image];
  d.textures = [{ source: 0 }];
  d.materials[0].pbrMetallicRoughness = { baseColorTexture: { index: 0 } };
};

// `chunks` lists the chunks after JSON as [type, bytes]; default: the BIN chunk.
function glbBytes(doc, bin, chunks) {
  const pad = (buf, fill) => Buffer.concat([buf, Buffer.alloc((4 - (buf.length % 4)) % 4, fill)]);
  const json = pad(Buffer.from(JSON.stringify(doc)), 0x20);
  const chunk = (type, data) => {
    const h = Buffer.alloc(8); h.writeUInt32LE(data.length, 0); h.writeUInt32LE(type, 4);
    return Buffer.concat([h, data]);
  };
  const rest = (chunks || [[0x004e4942, bin]]).map(([type, data]) => chunk(type, pad(data, 0)));
  const body = Buffer.concat([chunk(0x4e4f534a, json), ...rest]);
  const header = Buffer.alloc(12);
  header.write('glTF', 0); header.writeUInt32LE(2, 4); header.writeUInt32LE(12 + body.length, 8);
  return Buffer.concat([header, body]);
}

function glb(name, where, phrase, mutateBytes, mutateDoc, chunks) {
  const bin = triangleBin();
  const doc = base(bin);
  delete doc.buffers[0].uri;
  if (mutateDoc) mutateDoc(doc);
  const bytes = glbBytes(doc, bin, chunks);
  writeFileSync(join(dir, name), mutateBytes ? mutateBytes(bytes) : bytes);
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
  d.extensionsUsed = d.extensionsRequired = ['KHR_texture_basisu'];
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


// --- Added for issue 7 (every failure class of its list) ---------------------------------
const BIN = 0x004e4942, JSON_CHUNK = 0x4e4f534a;
// The container.
glb('glb_header_short.glb', 'glb.header', 'shorter than the 12-byte', b => b.subarray(0, 10));
glb('glb_length_short.glb', 'glb.header.length', 'but the file has', b => { b.writeUInt32LE(b.length - 4, 8); return b; });
glb('glb_chunk_unaligned.glb', 'glb.chunks[0].chunkLength', 'multiple of 4', b => { b.writeUInt32LE(b.readUInt32LE(12) - 2, 12); return b; });
glb('glb_chunk_header_cut.glb', 'glb.chunks[2]', 'needs 8 bytes', b => {
  const out = Buffer.concat([b, Buffer.alloc(4)]); out.writeUInt32LE(out.length, 8); return out;
});
glb('glb_two_bin_chunks.glb', 'glb.chunks[2].chunkType', 'only one', null, null, [[BIN, triangleBin()], [BIN, triangleBin()]]);
glb('glb_second_json_chunk.glb', 'glb.chunks[1].chunkType', 'second JSON chunk', null, null, [[JSON_CHUNK, Buffer.from('{}  ')]]);
glb('glb_bin_missing.glb', 'buffers[0].byteLength', 'BIN chunk has 0', null, null, []);
glb('glb_buffer_longer_than_bin.glb', 'buffers[0].byteLength', 'BIN chunk has 80', null, d => { d.buffers[0].byteLength = 96; });
glb('glb_second_buffer_without_uri.glb', 'buffers[1].uri', 'only buffers[0] of a GLB', null, d => { d.buffers.push({ byteLength: 4 }); });
// JSON and the document's shape (tinygltf would ignore a wrong type or narrow an index).
writeFileSync(join(dir, 'json_root_array.gltf'), '[{"asset": {"version": "2.0"}}]\n');
expected['json_root_array.gltf'] = { where: 'json_root_array.gltf', phrase: 'root must be an object' };
gltf('json_number_overflow.gltf', 'json_number_overflow.gltf', 'not valid JSON', d => { d.nodes[0].translation = [7, 0, 0]; },
  undefined, text => text.replace(/"translation": \[\s*7/, '"translation": [1e400'));
gltf('asset_missing.gltf', 'asset', 'is required', d => { delete d.asset; });
gltf('asset_version_1.gltf', 'asset.version', 'must be "2.0"', d => { d.asset.version = '1.0'; });
gltf('array_not_array.gltf', 'nodes', 'must be an array', d => { d.nodes = { mesh: 0 }; });
gltf('array_item_not_object.gltf', 'meshes[0].primitives[0]', 'must be a JSON object', d => { d.meshes[0].primitives = [4]; });
gltf('object_not_object.gltf', 'materials[0].pbrMetallicRoughness', 'must be a JSON object', d => { d.materials[0].pbrMetallicRoughness = ['not an object']; });
gltf('name_not_string.gltf', 'scenes[0].name', 'must be a string', d => { d.scenes[0].name = 42; });
gltf('extension_not_object.gltf', 'nodes[0].extensions.EXT_example', 'must be a JSON object', d => { d.nodes[0].extensions = { EXT_example: 'no' }; });
gltf('number_is_string.gltf', 'materials[0].pbrMetallicRoughness.metallicFactor', 'must be a number', d => { d.materials[0].pbrMetallicRoughness = { metallicFactor: '1' }; });
gltf('index_is_string.gltf', 'nodes[0].mesh', 'must be an index into meshes', d => { d.nodes[0].mesh = '0'; });
gltf('index_is_fraction.gltf', 'nodes[0].mesh', 'must be an index into meshes', d => { d.nodes[0].mesh = 0.5; });
gltf('index_wraps_int.gltf', 'nodes[0].mesh', 'meshes[4294967296] does not exist', d => { d.nodes[0].mesh = 4294967296; });
gltf('index_negative.gltf', 'materials[0].pbrMetallicRoughness.baseColorTexture.index', 'must be an index into textures', d => {
  d.materials[0].pbrMetallicRoughness = { baseColorTexture: { index: -1 } };
});
// Every index.
gltf('scene_index_missing.gltf', 'scene', 'scenes[3] does not exist', d => { d.scene = 3; });
gltf('scene_index_not_integer.gltf', 'scene', 'must be an index into scenes', d => { d.scene = 'hello'; });
gltf('scene_node_listed_twice.gltf', 'scenes[0].nodes[1]', 'listed twice', d => { d.scenes[0].nodes = [0, 0]; });
gltf('node_children_listed_twice.gltf', 'nodes[0].children[1]', 'listed twice', d => { d.nodes.push({}); d.nodes[0].children = [1, 1]; });
gltf('accessor_view_missing.gltf', 'accessors[0].bufferView', 'bufferViews[7] does not exist', d => { d.accessors[0].bufferView = 7; });
gltf('attribute_index_missing.gltf', 'meshes[0].primitives[0].attributes.COLOR_0', 'accessors[77] does not exist', d => {
  d.meshes[0].primitives[0].attributes.COLOR_0 = 77;
});
gltf('morph_target_index_missing.gltf', 'meshes[0].primitives[0].targets[0].POSITION', 'accessors[9] does not exist', d => {
  d.meshes[0].primitives[0].targets = [{ POSITION: 9 }];
});
gltf('indices_index_missing.gltf', 'meshes[0].primitives[0].indices', 'accessors[5] does not exist', d => { d.meshes[0].primitives[0].indices = 5; });
gltf('texture_index_missing.gltf', 'materials[0].pbrMetallicRoughness.baseColorTexture.index', 'textures[3] does not exist', d => {
  d.materials[0].pbrMetallicRoughness = { baseColorTexture: { index: 3 } };
});
gltf('unused_texture_index_missing.gltf', 'materials[0].occlusionTexture.index', 'textures[0] does not exist', d => {
  d.materials[0].occlusionTexture = { index: 0 };
});
gltf('texture_source_missing.gltf', 'textures[0].source', 'images[4] does not exist', d => {
  textured({ uri: dataUri('image/png', png(1, 1)) })(d); d.textures[0].source = 4;
});
gltf('texture_sampler_missing.gltf', 'textures[0].sampler', 'samplers[2] does not exist', d => {
  textured({ uri: dataUri('image/png', png(1, 1)) })(d); d.textures[0].sampler = 2;
});
gltf('image_view_missing.gltf', 'images[0].bufferView', 'bufferViews[9] does not exist', d => { d.images = [{ bufferView: 9, mimeType: 'image/png' }]; });
gltf('texcoord_negative.gltf', 'materials[0].pbrMetallicRoughness.baseColorTexture.texCoord', 'integer in [0', d => {
  textured({ uri: dataUri('image/png', png(1, 1)) })(d); d.materials[0].pbrMetallicRoughness.baseColorTexture.texCoord = -1;
});
gltf('camera_index_missing.gltf', 'nodes[0].camera', 'cameras[3] does not exist', d => { d.nodes[0].camera = 3; });
gltf('light_index_missing.gltf', 'nodes[0].extensions.KHR_lights_punctual.light', 'lights[4] does not exist', d => {
  d.extensionsUsed = ['KHR_lights_punctual'];
  d.extensions = { KHR_lights_punctual: { lights: [{ type: 'point' }] } };
  d.nodes[0].extensions = { KHR_lights_punctual: { light: 4 } };
});
gltf('skin_index_missing.gltf', 'nodes[0].skin', 'skins[2] does not exist', d => { d.nodes[0].skin = 2; });
gltf('skin_joint_missing.gltf', 'skins[0].joints[0]', 'nodes[5] does not exist', d => { d.skins = [{ joints: [5] }]; });
gltf('animation_sampler_missing.gltf', 'animations[0].channels[0].sampler', 'samplers[3] does not exist', d => {
  d.animations = [{ samplers: [{ input: 0, output: 0 }], channels: [{ sampler: 3, target: { node: 0, path: 'translation' } }] }];
});
gltf('animation_accessor_missing.gltf', 'animations[0].samplers[0].input', 'accessors[9] does not exist', d => {
  d.animations = [{ samplers: [{ input: 9, output: 0 }], channels: [{ sampler: 0, target: { node: 0, path: 'translation' } }] }];
});
gltf('sparse_view_missing.gltf', 'accessors[3].sparse.indices.bufferView', 'bufferViews[9] does not exist', d => {
  d.accessors.push({ bufferView: 0, componentType: 5126, count: 3, type: 'VEC3',
    sparse: { count: 1, indices: { bufferView: 9, componentType: 5123 }, values: { bufferView: 0 } } });
});
gltf('sparse_indices_float.gltf', 'accessors[3].sparse.indices.componentType', 'must be one of', d => {
  d.accessors.push({ bufferView: 0, componentType: 5126, count: 3, type: 'VEC3',
    sparse: { count: 1, indices: { bufferView: 1, componentType: 5126 }, values: { bufferView: 0 } } });
});
// Byte ranges (64-bit), alignment and strides.
gltf('buffer_uri_missing.gltf', 'buffers[0].uri', 'is required in a .gltf', d => { delete d.buffers[0].uri; });
gltf('buffer_length_zero.gltf', 'buffers[0].byteLength', '>= 1', d => { d.buffers[0].byteLength = 0; });
gltf('view_length_zero.gltf', 'bufferViews[1].byteLength', '>= 1', d => { d.bufferViews[1].byteLength = 0; });
gltf('view_offset_near_2_64.gltf', 'bufferViews[1].byteLength', 'run past', d => { d.bufferViews[1].byteOffset = 1234567; },
  undefined, replaceOnce('"byteOffset": 1234567', '"byteOffset": 18446744073709551610'));
gltf('accessor_offset_near_2_64.gltf', 'accessors[0].byteOffset', 'lies past', d => { d.accessors[0].byteOffset = 1234568; },
  undefined, replaceOnce('"byteOffset": 1234568', '"byteOffset": 18446744073709551612'));
gltf('accessor_offset_negative.gltf', 'accessors[0].byteOffset', 'non-negative integer', d => { d.accessors[0].byteOffset = -4; });
gltf('accessor_count_zero.gltf', 'accessors[0].count', '>= 1', d => { d.accessors[0].count = 0; });
gltf('accessor_view_absent.gltf', 'accessors[0].bufferView', 'not supported', d => { delete d.accessors[0].bufferView; });
gltf('accessor_component_type_invalid.gltf', 'accessors[0].componentType', 'must be one of', d => { d.accessors[0].componentType = 5130; });
gltf('accessor_type_invalid.gltf', 'accessors[0].type', 'must be one of', d => { d.accessors[0].type = 'VEC5'; });
gltf('view_offset_misaligned.gltf', 'accessors[0].byteOffset', 'aligned', d => {
  d.bufferViews[0].byteOffset = 2; d.bufferViews[0].byteLength = 70;
});
gltf('view_stride_not_multiple_of_4.gltf', 'bufferViews[0].byteStride', 'multiple of 4', d => { d.bufferViews[0].byteStride = 14; });
gltf('view_stride_below_element.gltf', 'bufferViews[0].byteStride', 'smaller than', d => { d.bufferViews[0].byteStride = 8; });
gltf('index_view_has_stride.gltf', 'bufferViews[1].byteStride', 'must not be set', d => {
  d.bufferViews[1] = { buffer: 0, byteOffset: 64, byteLength: 16, byteStride: 4 };
});
// Attribute types and counts.
gltf('position_missing.gltf', 'meshes[0].primitives[0].attributes.POSITION', 'is required', d => {
  d.meshes[0].primitives[0].attributes = { NORMAL: 1 };
});
gltf('attribute_normalized_float.gltf', 'accessors[1].componentType', 'normalized FLOAT', d => { d.accessors[1].normalized = true; });
gltf('attribute_unread_count_differs.gltf', 'meshes[0].primitives[0].attributes.COLOR_0', 'POSITION has 3', d => {
  d.accessors.push({ bufferView: 0, componentType: 5126, count: 2, type: 'VEC3' });
  d.meshes[0].primitives[0].attributes.COLOR_0 = 3;
});
// Primitive modes.
gltf('primitive_mode_not_integer.gltf', 'meshes[0].primitives[0].mode', 'not a glTF primitive mode', d => { d.meshes[0].primitives[0].mode = '4'; });
gltf('primitive_strip_too_short.gltf', 'meshes[0].primitives[0].indices', 'at least 3', d => {
  d.meshes[0].primitives[0].mode = 5; d.accessors[2].count = 2;
});
gltf('primitives_empty.gltf', 'meshes[0].primitives', 'must not be empty', d => { d.meshes[0].primitives = []; });
// Non-finite and out-of-range values.
gltf('position_inf.gltf', 'meshes[0].primitives[0].attributes.POSITION', 'inf', null, triangleBin({ infPosition: true }));
gltf('normal_nan.gltf', 'meshes[0].primitives[0].attributes.NORMAL', 'nan', null, triangleBin({ nanNormal: true }));
gltf('translation_not_float.gltf', 'nodes[0].translation[2]', 'fits a float', d => { d.nodes[0].translation = [0, 0, -1e300]; });
gltf('scale_not_number.gltf', 'nodes[0].scale[1]', 'must be a number', d => { d.nodes[0].scale = [1, null, 1]; });
gltf('rotation_wrong_length.gltf', 'nodes[0].rotation', 'array of 4 numbers', d => { d.nodes[0].rotation = [0, 0, 1]; });
gltf('matrix_with_trs.gltf', 'nodes[0].matrix', 'cannot be combined', d => {
  d.nodes[0].matrix = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]; d.nodes[0].translation = [1, 0, 0];
});
gltf('world_transform_overflow.gltf', 'nodes[1]', 'not finite in float precision', d => {
  d.nodes = [{ scale: [1e30, 1e30, 1e30], children: [1] }, { mesh: 0, scale: [1e30, 1e30, 1e30] }];
});
gltf('metallic_out_of_range.gltf', 'materials[0].pbrMetallicRoughness.metallicFactor', '[0, 1]', d => {
  d.materials[0].pbrMetallicRoughness = { metallicFactor: 1.5 };
});
gltf('normal_scale_huge.gltf', 'materials[0].normalTexture.scale', 'finite', d => {
  textured({ uri: dataUri('image/png', png(1, 1)) })(d);
  d.materials[0].normalTexture = { index: 0, scale: 1e300 };
});
gltf('camera_type_invalid.gltf', 'cameras[0].type', 'must be one of', d => { d.cameras = [{ type: 'fisheye' }]; d.nodes[0].camera = 0; });
gltf('camera_znear_not_number.gltf', 'cameras[0].perspective.znear', 'must be a number', d => {
  d.cameras = [{ type: 'perspective', perspective: { yfov: 1, znear: '0.1' } }]; d.nodes[0].camera = 0;
});
gltf('camera_ortho_zfar.gltf', 'cameras[0].orthographic.zfar', '> znear', d => {
  d.cameras = [{ type: 'orthographic', orthographic: { xmag: 1, ymag: 1, znear: 2, zfar: 1 } }]; d.nodes[0].camera = 0;
});
gltf('camera_node_degenerate.gltf', 'nodes[0]', 'degenerate world transform', d => {
  d.cameras = [{ type: 'perspective', perspective: { yfov: 1, znear: 0.1 } }]; d.nodes[0].camera = 0; d.nodes[0].scale = [0, 1, 1];
});
const light = (name, where, phrase, l) => gltf(name, where, phrase, d => {
  d.extensionsUsed = ['KHR_lights_punctual'];
  d.extensions = { KHR_lights_punctual: { lights: [l] } };
  d.nodes[0].extensions = { KHR_lights_punctual: { light: 0 } };
});
light('light_type_invalid.gltf', 'lights[0].type', 'must be one of', { type: 'area' });
light('light_intensity_negative.gltf', 'lights[0].intensity', '>= 0', { type: 'point', intensity: -3 });
light('light_color_wrong_length.gltf', 'lights[0].color', 'array of 3 numbers', { type: 'point', color: [1, 1] });
// Images: declared type, bytes, sizes.
gltf('image_uri_and_view.gltf', 'images[0]', 'exactly one of uri and bufferView', d => {
  d.images = [{ uri: 'a.png', bufferView: 0, mimeType: 'image/png' }];
});
gltf('image_mime_type_invalid.gltf', 'images[0].mimeType', 'must be one of', d => { d.images = [{ bufferView: 0, mimeType: 'image/gif' }]; });
gltf('image_view_no_mime_type.gltf', 'images[0].mimeType', 'is required', d => { d.images = [{ bufferView: 0 }]; });
gltf('image_uri_wrong_media_type.gltf', 'images[0].uri', 'type "application/octet-stream"', textured({
  uri: dataUri('application/octet-stream', png(1, 1)) }));
gltf('image_declared_jpeg_is_png.gltf', 'images[0].uri', 'declares image/jpeg but the bytes are image/png', textured({
  uri: dataUri('image/jpeg', png(1, 1)) }));
gltf('image_mime_type_contradicts_uri.gltf', 'images[0].mimeType', 'but the data URI is image/png', textured({
  uri: dataUri('image/png', png(1, 1)), mimeType: 'image/jpeg' }));
gltf('image_huge_dimensions.gltf', 'images[0].uri', 'larger than the limit', textured({ uri: dataUri('image/png', png(100000, 100000, { idat: false })) }));
gltf('image_pixels_missing.gltf', 'images[0].uri', 'cannot be decoded', textured({ uri: dataUri('image/png', png(4, 4, { idat: false })) }));
gltf('image_truncated.gltf', 'images[0].uri', 'past the end of the file', textured({ uri: dataUri('image/png', png(64, 64).subarray(0, 60)) }));
gltf('image_corrupt_pixels.gltf', 'images[0].uri', 'cannot be decoded', textured({ uri: dataUri('image/png', (() => {
  // Every chunk intact (lengths inside the file, IEND present), the IDAT's zlib stream garbled.
  const p = Buffer.from(png(64, 64));
  for (let i = 41; i < 49; ++i) p[i] = 0xff;
  return p;
})()) }));
gltf('image_view_not_an_image.gltf', 'images[0].bufferView', 'neither PNG nor JPEG', textured({ bufferView: 0, mimeType: 'image/png' }));
gltf('image_uri_dotdot.gltf', 'images[0].uri', '".." segment', textured({ uri: '../../etc/passwd' }));
// URIs.
gltf('uri_backslash.gltf', 'buffers[0].uri', 'backslash', d => { d.buffers[0].uri = '..\\secret.bin'; });
gltf('uri_percent_slash.gltf', 'buffers[0].uri', 'absolute path once percent-decoded', d => { d.buffers[0].uri = '%2fetc/passwd'; });
gltf('uri_percent_nul.gltf', 'buffers[0].uri', 'control character', d => { d.buffers[0].uri = 'triangle.bin%00.png'; });
gltf('uri_drive_letter.gltf', 'buffers[0].uri', 'scheme', d => { d.buffers[0].uri = 'C:/Windows/win.ini'; });
gltf('image_file_missing.gltf', 'images[0].uri', 'no such file', textured({ uri: 'missing.png' }));
gltf('buffer_file_missing.gltf', 'buffers[0].uri', 'no such file', d => { d.buffers[0].uri = 'missing.bin'; });
gltf('uri_is_a_folder.gltf', 'buffers[0].uri', 'not a regular file', d => { d.buffers[0].uri = '.'; });
// A message from tinygltf counts even when it returned success: an image file it cannot
// read (here: empty) is only a warning to tinygltf 2.7.0 (ParseImage), an error here.
writeFileSync(join(dir, 'empty.png'), '');
gltf('image_file_empty.gltf', 'empty.png', 'tinygltf', textured({ uri: 'empty.png' }));

writeFileSync(join(dir, 'expected.json'), JSON.stringify(expected, null, 1) + '\n');
console.log(`${Object.keys(expected).length} files`);

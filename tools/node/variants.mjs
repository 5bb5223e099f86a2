// Writes variants of a glTF file with glTF-Transform (npm @gltf-transform/core and
// /extensions, with the Draco and meshoptimizer encoders from npm), so that the loader is
// tested on files written by a tool not ours (issue 21). Installed by
// scripts/install-deps.sh into tools/node/node_modules.
//
// Usage: node tools/node/variants.mjs IN OUT VARIANT [--material N] [--json '{...}']
//   draco        KHR_draco_mesh_compression (edgebreaker; POSITION 14 bits, NORMAL 10,
//                TEXCOORD 12: glTF-Transform's defaults, written out)
//   meshopt      EXT_meshopt_compression without filters (the float data as it is)
//   meshopt-filter  EXT_meshopt_compression with glTF-Transform's filters (NORMAL and
//                TANGENT octahedral, 8 bits, as normalized BYTE: KHR_mesh_quantization)
//   decode       the same file without EXT_meshopt_compression and KHR_draco_mesh_compression:
//                glTF-Transform decodes them (the npm meshoptimizer and draco3dgltf
//                decoders) and writes the data uncompressed, still quantized
//   volume       KHR_materials_volume, KHR_materials_ior and KHR_materials_transmission on
//                materials[N] (default 0), from --json: {"thicknessFactor", "attenuationDistance",
//                "attenuationColor", "ior", "transmissionFactor", "diffuseTransmissionFactor"}; with "multiscatterColor"
//                and "scatterAnisotropy" also the draft KHR_materials_volume_scatter, which
//                glTF-Transform does not implement: the script defines it as a glTF-Transform
//                extension (below). extras stay as they are unless "dropExtras": true
// Exit status: 0 written, 1 a tool error (the message says which), 2 bad arguments.
import { Extension, ExtensionProperty, NodeIO, PropertyType } from '@gltf-transform/core';
import {
  ALL_EXTENSIONS, EXTMeshoptCompression, KHRDracoMeshCompression, KHRMaterialsDiffuseTransmission,
  KHRMaterialsIOR, KHRMaterialsTransmission, KHRMaterialsVolume, KHRMeshQuantization,
} from '@gltf-transform/extensions';
import draco3d from 'draco3dgltf';
import { MeshoptDecoder, MeshoptEncoder } from 'meshoptimizer';

// The draft KHR_materials_volume_scatter (KhronosGroup/glTF PR #2453), written only:
// its two factors, on the materials that carry it. Drafts go in extensionsUsed only.
const SCATTER = 'KHR_materials_volume_scatter';
class VolumeScatter extends ExtensionProperty {
  static EXTENSION_NAME = SCATTER;
  init() {
    this.extensionName = SCATTER;
    this.propertyType = 'VolumeScatter';
    this.parentTypes = [PropertyType.MATERIAL];
  }
  getDefaults() {
    return Object.assign(super.getDefaults(), { multiscatterColor: [0, 0, 0], scatterAnisotropy: 0 });
  }
}
class KHRMaterialsVolumeScatter extends Extension {
  static EXTENSION_NAME = SCATTER;
  extensionName = SCATTER;
  create(multiscatterColor, scatterAnisotropy) {
    const p = new VolumeScatter(this.document.getGraph());
    p.set('multiscatterColor', multiscatterColor);
    p.set('scatterAnisotropy', scatterAnisotropy);
    return p;
  }
  read() { return this; }
  write(context) {
    const json = context.jsonDoc.json;
    for (const material of this.document.getRoot().listMaterials()) {
      const p = material.getExtension(SCATTER);
      if (!p) continue;
      const def = json.materials[context.materialIndexMap.get(material)];
      def.extensions = def.extensions || {};
      def.extensions[SCATTER] = { multiscatterColor: p.get('multiscatterColor'), scatterAnisotropy: p.get('scatterAnisotropy') };
    }
    return this;
  }
}

const usage = 'usage: node variants.mjs IN OUT draco|meshopt|meshopt-filter|decode|volume [--material N] [--json JSON]';
const args = process.argv.slice(2);
if (args.includes('--help') || args.includes('-h')) {
  console.log(usage);
  process.exit(0);
}
const [input, output, variant] = args;
const option = (name) => {
  const i = args.indexOf(name);
  return i >= 0 ? args[i + 1] : undefined;
};
if (!input || !output || !['draco', 'meshopt', 'meshopt-filter', 'decode', 'volume'].includes(variant)) {
  console.error(usage);
  process.exit(2);
}

try {
  await MeshoptEncoder.ready;
  await MeshoptDecoder.ready;
  const io = new NodeIO().registerExtensions([...ALL_EXTENSIONS, KHRMaterialsVolumeScatter]).registerDependencies({
    'draco3d.decoder': await draco3d.createDecoderModule(),
    'draco3d.encoder': await draco3d.createEncoderModule(),
    'meshopt.decoder': MeshoptDecoder,
    'meshopt.encoder': MeshoptEncoder,
  });
  const doc = await io.read(input);
  if (variant === 'draco') {
    doc.createExtension(KHRDracoMeshCompression).setRequired(true).setEncoderOptions({
      method: KHRDracoMeshCompression.EncoderMethod.EDGEBREAKER,
      quantizationBits: { POSITION: 14, NORMAL: 10, TEX_COORD: 12, COLOR: 8, GENERIC: 12 },
    });
  } else if (variant.startsWith('meshopt')) {
    // The filters store normals as normalized BYTE, which KHR_mesh_quantization allows.
    if (variant === 'meshopt-filter') doc.createExtension(KHRMeshQuantization).setRequired(true);
    doc.createExtension(EXTMeshoptCompression).setRequired(true).setEncoderOptions({
      method: variant === 'meshopt-filter' ? EXTMeshoptCompression.EncoderMethod.FILTER
                                           : EXTMeshoptCompression.EncoderMethod.QUANTIZE,
    });
  } else if (variant === 'decode') {
    for (const e of doc.getRoot().listExtensionsUsed())
      if (e.extensionName === 'EXT_meshopt_compression' || e.extensionName === 'KHR_draco_mesh_compression') e.dispose();
  } else {
    const spec = JSON.parse(option('--json') ?? '{}');
    const index = Number(option('--material') ?? 0);
    const material = doc.getRoot().listMaterials()[index];
    if (!material) throw new Error(`${input}: materials[${index}] does not exist`);
    const volume = doc.createExtension(KHRMaterialsVolume).createVolume();
    if (spec.thicknessFactor !== undefined) volume.setThicknessFactor(spec.thicknessFactor);
    if (spec.attenuationDistance !== undefined) volume.setAttenuationDistance(spec.attenuationDistance);
    if (spec.attenuationColor !== undefined) volume.setAttenuationColor(spec.attenuationColor);
    material.setExtension('KHR_materials_volume', volume);
    if (spec.ior !== undefined)
      material.setExtension('KHR_materials_ior', doc.createExtension(KHRMaterialsIOR).createIOR().setIOR(spec.ior));
    if (spec.transmissionFactor !== undefined)
      material.setExtension('KHR_materials_transmission',
                            doc.createExtension(KHRMaterialsTransmission).createTransmission()
                              .setTransmissionFactor(spec.transmissionFactor));
    if (spec.diffuseTransmissionFactor !== undefined)
      material.setExtension('KHR_materials_diffuse_transmission',
                            doc.createExtension(KHRMaterialsDiffuseTransmission).createDiffuseTransmission()
                              .setDiffuseTransmissionFactor(spec.diffuseTransmissionFactor));
    if (spec.multiscatterColor !== undefined)
      material.setExtension(SCATTER, doc.createExtension(KHRMaterialsVolumeScatter)
                                       .create(spec.multiscatterColor, spec.scatterAnisotropy ?? 0));
    if (spec.dropExtras) material.setExtras({});
  }
  await io.write(output, doc);
} catch (e) {
  console.error(`variants.mjs: ${e.message ?? e}`);
  process.exit(1);
}

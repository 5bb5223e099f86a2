# sss_embed_shaders(TARGET file...) — placeholder until renderer/vk lands its version.

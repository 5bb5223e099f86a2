# The fuzz target bodies (fuzz/FuzzTargets.h), compiled into the libFuzzer executables
# (fuzz/CMakeLists.txt, clang) and into the replay test (tests/CMakeLists.txt, any compiler).
set(SSS_FUZZ_BODY_SOURCES
    ${CMAKE_CURRENT_LIST_DIR}/FuzzSupport.cpp
    ${CMAKE_CURRENT_LIST_DIR}/fuzz_gltf.cpp
    ${CMAKE_CURRENT_LIST_DIR}/fuzz_sss_extras.cpp
    ${CMAKE_CURRENT_LIST_DIR}/fuzz_medium_args.cpp
    ${CMAKE_CURRENT_LIST_DIR}/fuzz_image.cpp)
set(SSS_FUZZ_BODY_LIBS sss_scene sss_image sss_app_materials nlohmann_json::nlohmann_json)
set(SSS_FUZZ_TARGET_NAMES gltf sss_extras medium_args image)

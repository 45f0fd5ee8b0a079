// tinygltf's implementation compiled into the glTF fuzzer, with the fuzzer's instrumentation
// (coverage, ASan, UBSan), in place of Debian's prebuilt libtinygltf.so: the same header and
// version (libtinygltf-dev), so the loader's calls bind to these definitions and the JSON
// parsing and accessor code are fuzzed as well as saagen's. PNG and JPEG decoding stays in
// Debian's libstb (the png target covers it).
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>

// Runs a libFuzzer target's LLVMFuzzerTestOneInput on the files named on the command line, without libFuzzer:
// make test replays the inputs kept in tests/fuzz/corpus/ (each once stopped a target, or is a configuration
// that once broke the clipper), so that the targets keep building with the project's compiler and those
// inputs keep passing. A failing input aborts (the target's trap).
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    std::ifstream in(argv[i], std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "replay: cannot read %s\n", argv[i]);
      return 2;
    }
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
    std::printf("replay: %s passed (%zu bytes)\n", argv[i], bytes.size());
  }
  return 0;
}

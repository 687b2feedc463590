// tumble_model_import FILE SCALE: reads one model file with assimp and
// stb_image (render::loadModelInThisProcess) and writes the model, or the
// error, as bytes to standard output. render::loadModel starts it for every
// model, so that a file that crashes or hangs assimp takes down this
// process, not the game (render/internal/model_import.h). SCALE is a
// hexadecimal float ("%a").
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/log.h"
#include "render/internal/model_import.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr,
                 "usage: tumble_model_import FILE SCALE\n"
                 "  tumble starts this to read a model file in a process of its own; it writes the model as bytes\n");
    return 2;
  }
  // A damaged file can make assimp ask for tens of gigabytes (the model
  // fuzzer found a 48 GB request inside libassimp); this process may have
  // 8 GiB of address space, more than the largest model the loader takes
  // needs (its answer is capped at 2 GiB), so such a file fails here
  // instead of pushing the machine into swap. Not under AddressSanitizer,
  // whose shadow memory is a far larger mapping.
#if !defined(__SANITIZE_ADDRESS__) && !(defined(__has_feature) && __has_feature(address_sanitizer))
  const rlimit space{rlim_t(8) << 30, rlim_t(8) << 30};
  ::setrlimit(RLIMIT_AS, &space);
#endif
  // Warnings travel in the answer (Model::warnings) and the game logs them.
  tumble::log::setLevel(tumble::log::Level::Error);
  tumble::render::ModelLoadOptions options;
  char* end = nullptr;
  options.scale = std::strtof(argv[2], &end);
  if (end == argv[2] || *end != '\0') options.scale = 0;  // refused with a message by the loader
  const std::string bytes = tumble::render::encodeImportResult(tumble::render::loadModelInThisProcess(argv[1], options));
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::write(1, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) _exit(3);
    done += std::size_t(n);
  }
  // No exit-time work: Debian's assimp leaks on some damaged files, and a
  // leak check at exit would turn a refused file into a failed import.
  _exit(0);
}

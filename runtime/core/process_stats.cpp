#include "core/process_stats.h"

#include <sys/resource.h>

namespace tumble {

double peakRssMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // Linux reports KiB
}

}  // namespace tumble

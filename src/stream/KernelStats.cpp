#include "stream/KernelStats.h"

namespace gpurt {

KernelStats& KernelStats::global() {
    static KernelStats stats;
    return stats;
}

}  // namespace gpurt

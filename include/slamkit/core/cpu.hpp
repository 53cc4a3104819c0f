#pragma once

namespace slamkit {

// The number of CPUs this process may run on: its affinity mask (taskset, cgroups' cpusets),
// not the machine's core count, so "all CPUs" never asks for workers the process cannot use.
// At least 1.
int UsableCpuCount() noexcept;

}  // namespace slamkit

#pragma once
// Peak resident memory and processor time of this process, for the cost columns of a study. Linux
// keeps the high-water mark (VmHWM in /proc/self/status) for the life of a process; writing "5" to
// /proc/self/clear_refs resets it to the current RSS (Linux >= 4.0), so each level of a study
// that runs in one process measures its own peak. Where the reset is refused, the value is
// the process's peak so far, which for a ladder run coarsest first is still the level's own
// peak up to the memory the earlier, smaller levels left allocated.
namespace sph::study {

// Bytes; 0 when /proc is not available.
double peak_resident_bytes();

// True when the high-water mark was reset.
bool reset_peak_resident();

// Processor time (user + system) this process has used so far [s].
double process_cpu_seconds();

}  // namespace sph::study

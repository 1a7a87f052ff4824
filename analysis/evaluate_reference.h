#pragma once
// The error of one run against its case's reference (Case.reference), read from the run's
// result.h5: the one entry point that convergence studies and validation tests share, so
// both measure the same thing.
#include <string>
#include <vector>

#include "analysis/measurement.h"
#include "sph/v1/case.pb.h"

namespace sph::analysis {

// Throws std::runtime_error (naming the reference field where one is at fault) when the
// result lacks what the reference needs. For a Richardson reference only `quantity` is set;
// complete_richardson fills in the errors once the ladder is complete.
Measurement evaluate_reference(const v1::Case& c, const std::string& result_h5);

// Richardson references: the error of every level from the quantities of the levels with a
// finite one (dx coarsest first). Returns "" or why no estimate could be made (the errors
// then stay NaN). Other kinds are left unchanged.
std::string complete_richardson(const v1::Case& c, const std::vector<double>& dx,
                                std::vector<Measurement>& levels);

// One line: what the error of this reference is (for reports and plot titles).
std::string describe_reference(const v1::Case& c);

}  // namespace sph::analysis

#pragma once
// Start-up flows between parallel plates (Adami 2012 sec. 5.1, series solutions of the
// diffusion equation for u_x(y, t) from rest): Poiseuille flow driven by a body force,
// Couette flow driven by the upper wall, and their superposition.
#include "analysis/measurement.h"
#include "analysis/result_reader.h"
#include "sph/v1/case.pb.h"

namespace sph::analysis {

// y measured from the lower plate, plates at 0 and height.
double poiseuille_startup(double y, double t, double body_force, double nu, double height);
double couette_startup(double y, double t, double wall_velocity, double nu, double height);

// u_x at absolute y for the reference's flow.
double channel_flow_velocity(const v1::ChannelFlowReference& r, double y, double t);
// velocity_scale, or its default (see case.proto).
double channel_flow_velocity_scale(const v1::ChannelFlowReference& r);

// Mean |u_x - u_exact| over the fluid particles of the snapshot / velocity scale.
Measurement channel_flow_error(const Snapshot& s, const v1::ChannelFlowReference& r);

}  // namespace sph::analysis

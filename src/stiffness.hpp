// Static stability of an equilibrium: the lowest eigenvalue of the stiffness matrix
// (the Hessian of the potential energy), by central differences of the forces.
// Negative: the state is unstable (a buckling load has been passed). Exact for the
// discrete model, unlike trial runs that watch a perturbation grow or decay.
#pragma once

namespace slender {

class Simulation;

struct StiffnessResult {
  double lowest = 0.0;  // lowest eigenvalue (force per length; frames: per quaternion unit)
  int dofs = 0;         // degrees of freedom kept (held ones are dropped)
};

// Degrees of freedom: every node's position components and, for each free rod frame,
// three directions tangent to |q| = 1. A degree of freedom whose force stays zero when
// it moves (a clamp) is dropped. Free modes (a rigid motion, the twist of a free rod
// end) have eigenvalue zero up to the error of the differences (about 1e-10 in the
// buckling deck): test instability against a small negative tolerance in the units of
// the problem. The state is restored on return, except the friction springs of contact
// pairs and walls, which advance with every force evaluation: use it without friction.
StiffnessResult lowest_stiffness(Simulation& sim, double eps);

}  // namespace slender

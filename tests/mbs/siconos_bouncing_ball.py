#!/usr/bin/python3
"""Siconos' own Moreau-Jean time stepping on the bouncing ball (the peer of
tests/mbs/moreau_jean_test.cc): the BouncingBallTS example of siconos-tutorials
(LagrangianLinearTIDS ball, NewtonImpactNSL e, LagrangianLinearTIR, MoreauJeanOSI theta,
TimeStepping with an LCP), on the data the flexmbs test gives on the command line.

usage: siconos_bouncing_ball.py GAP0 RADIUS MASS GRAVITY RESTITUTION STEP THETA END_TIME
prints one line per step: t [s], centre height q [m], velocity v [m/s], normal impulse p [N s].
Exit 77 if siconos is not installed (the test skips)."""
import sys

try:
    from siconos.kernel import (LagrangianLinearTIDS, NewtonImpactNSL, LagrangianLinearTIR,
                                Interaction, NonSmoothDynamicalSystem, MoreauJeanOSI,
                                TimeDiscretisation, LCP, TimeStepping)
    import numpy as np
except ImportError as error:
    print(f"siconos not available: {error}", file=sys.stderr)
    sys.exit(77)


def main():
    gap0, radius, mass, gravity, restitution, step, theta, end_time = map(float, sys.argv[1:9])
    # Generalised coordinates as in BouncingBallTS: (height of the centre, horizontal, rotation).
    q0 = [gap0 + radius, 0.0, 0.0]
    v0 = [0.0, 0.0, 0.0]
    mass_matrix = np.eye(3) * mass
    mass_matrix[2, 2] = 2.0 / 5.0 * mass * radius * radius
    ball = LagrangianLinearTIDS(q0, v0, mass_matrix)
    ball.setFExtPtr(np.array([-mass * gravity, 0.0, 0.0]))
    # The gap y = q_0 - r (H q + b).
    relation = LagrangianLinearTIR(np.array([[1.0, 0.0, 0.0]]), np.array([-radius]))
    interaction = Interaction(NewtonImpactNSL(restitution), relation)
    system = NonSmoothDynamicalSystem(0.0, end_time)
    system.insertDynamicalSystem(ball)
    system.link(interaction, ball)
    integrator = MoreauJeanOSI(theta)
    problem = LCP()
    simulation = TimeStepping(system, TimeDiscretisation(0.0, step), integrator, problem)
    q, v, p = ball.q(), ball.velocity(), ball.p(1)
    print(f"{0.0:.17g} {q[0]:.17g} {v[0]:.17g} {0.0:.17g}")
    while simulation.hasNextEvent():
        simulation.computeOneStep()
        print(f"{simulation.nextTime():.17g} {q[0]:.17g} {v[0]:.17g} {p[0]:.17g}")
        simulation.nextStep()


if __name__ == "__main__":
    main()

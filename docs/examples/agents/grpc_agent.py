"""A minimal external agent for seatwin's closed loop, built only from the protos (``seatwin.api.proto``'s generated
modules: ``agent_link.proto`` and Gemini's ``force_control.proto``) and ``grpc`` — no seatwin agent class.

It is a client of the simulation's ``AgentLink`` service: ``Observe`` gives a mission, then one step at a time (its own
navigation, the true targets), and it answers every step with one command before asking for the next. The policy
(:func:`decide`) is line-of-sight guidance to the goal with a 40° turn to starboard while a target's closest approach
is nearer than 25 m within 60 s — deliberately simple; the point is the transport.

    python docs/examples/agents/grpc_agent.py HOST:PORT [--mode velocity|force|gemini-force|thrust] [--one-call] [--keep]

``--mode``: a speed/heading set-point (``SetVelocity``), a force in doubles (``ApplyForce``), a force through Gemini's
``ForceControl.ApplyForce`` (floats), or thruster azimuths and thrusts (``ApplyThrust``); ``--one-call``: each command
sent with ``Act``, whose answer is the next observation (one call a step instead of two; not with Gemini's force).
``--keep``: after the simulation ends, wait for the next one at the same address (an agent serving a whole campaign).
``--sleep``, ``--die-at``, ``--hang-at``: a slow, a crashing and a hanging agent, for tests.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time

TURN = math.radians(40.0)
"""The turn to starboard while a target is dangerous."""


def _wrap(a: float) -> float:
    return math.remainder(a, 2.0 * math.pi)


def decide(
    goal: tuple[float, float], cruise: float, own: tuple[float, ...], targets: list[tuple[float, float, float, float]]
) -> tuple[float, float]:
    """(speed [m/s], course [rad]) from the goal (north, east), the cruise speed, the ownship's (north, east, heading,
    u, v, r) and the targets' (north, east, v_north, v_east)."""
    n, e, psi, u, v, _ = own
    dn, de = goal[0] - n, goal[1] - e
    dist = math.hypot(dn, de)
    course = math.atan2(de, dn)
    speed = cruise if dist > 10.0 else cruise * dist / 10.0
    vn, ve = u * math.cos(psi) - v * math.sin(psi), u * math.sin(psi) + v * math.cos(psi)
    for tn, te, tvn, tve in targets:
        rn, re, wn, we = tn - n, te - e, tvn - vn, tve - ve
        w2 = wn * wn + we * we
        tcpa = -(rn * wn + re * we) / w2 if w2 > 1e-9 else 0.0
        if 0.0 < tcpa < 60.0 and math.hypot(rn + wn * tcpa, re + we * tcpa) < 25.0:
            course = _wrap(course + TURN)
            break
    return speed, course


def force(speed: float, course: float, own: tuple[float, ...]) -> tuple[float, float, float]:
    """A proportional-derivative force (X [N], Y [N], N [N m]) towards the set-point."""
    _, _, psi, u, _, r = own
    return 300.0 * (speed - u) + 80.0 * u, 0.0, 300.0 * _wrap(course - psi) - 500.0 * r


def thrust(speed: float, course: float, own: tuple[float, ...]) -> tuple[tuple[float, float], tuple[float, float]]:
    """Both azimuths turned with the heading error (at most 0.5 rad), half the surge force each."""
    x, _, _ = force(speed, course, own)
    a = max(-0.5, min(0.5, 0.5 * _wrap(course - own[2])))
    return (a, a), (0.5 * x, 0.5 * x)


def _own(s) -> tuple[float, ...]:  # noqa: ANN001 - a State message
    return (s.north, s.east, s.heading, s.u, s.v, s.r)


def main(argv: list[str] | None = None) -> int:
    import grpc

    from seatwin.api.proto import agent_link_pb2, agent_link_pb2_grpc, force_control_pb2, force_control_pb2_grpc

    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("address", nargs="?", default=os.environ.get("SEATWIN_AGENT_ADDRESS"))
    p.add_argument("--mode", choices=("velocity", "force", "gemini-force", "thrust"), default="velocity")
    p.add_argument("--keep", action="store_true")
    p.add_argument("--one-call", action="store_true", help="Act: the command and the next observation in one call")
    p.add_argument("--sleep", type=float, default=0.0)
    p.add_argument("--die-at", type=int, default=-1)
    p.add_argument("--hang-at", type=int, default=-1)
    args = p.parse_args(argv)
    if not args.address:
        p.error("no address: give HOST:PORT or set SEATWIN_AGENT_ADDRESS")
    # reconnect within a second: waiting for the next simulation's server (--keep), gRPC's default backoff grows to 120 s
    backoff = [(f"grpc.{k}_reconnect_backoff_ms", v) for k, v in (("initial", 100), ("min", 100), ("max", 1000))]
    channel = grpc.insecure_channel(args.address, options=backoff)
    link = agent_link_pb2_grpc.AgentLinkStub(channel)
    gemini = force_control_pb2_grpc.ForceControlStub(channel)
    pb = agent_link_pb2
    mission, obs = None, None
    while True:
        if obs is None:  # (with --one-call, Act has brought the next observation already)
            try:
                obs = link.Observe(pb.ObserveRequest(agent="grpc_agent"), wait_for_ready=True)
            except grpc.RpcError as exc:
                if args.keep and exc.code() in (grpc.StatusCode.CANCELLED, grpc.StatusCode.UNAVAILABLE):
                    time.sleep(0.2)  # the last simulation's server went away under this call: wait for the next one
                    continue
                print(f"grpc_agent: Observe failed: {exc.code().name}: {exc.details()}", file=sys.stderr)
                return 1
        what, message, obs = obs.WhichOneof("what"), obs, None
        if what == "finished":
            if args.keep:
                time.sleep(0.2)  # the simulation's server is going away; the next one comes at the same address
                continue
            return 0
        if what == "mission":
            mission = message.mission
            continue
        step = message.step
        if step.index == args.die_at:
            print(f"grpc_agent: dying at step {step.index} as told", file=sys.stderr)
            return 3
        if step.index == args.hang_at:
            while True:
                time.sleep(60.0)
        if args.sleep:
            time.sleep(args.sleep)
        targets = [(t.north, t.east, t.v_north, t.v_east) for f in step.frames if f.sensor == "truth" for t in f.truth.targets]
        tracks = [pb.Track(id=i + 1, north=t[0], east=t[1], v_north=t[2], v_east=t[3]) for i, t in enumerate(targets)]
        own = _own(step.own)
        speed, course = decide((mission.goal_north, mission.goal_east), mission.cruise_speed, own, targets)
        if args.mode == "gemini-force":
            x, y, n = force(speed, course, own)
            tau = force_control_pb2.GeneralizedForce(x=x, y=y, n=n)
            gemini.ApplyForce(force_control_pb2.ForceRequest(vesselId=mission.vessel_id, generalizedForce=tau))
            continue
        if args.mode == "velocity":
            action = pb.Action(velocity=pb.VelocityRequest(step=step.index, speed=speed, heading=course, tracks=tracks))
        elif args.mode == "force":
            x, y, n = force(speed, course, own)
            action = pb.Action(force=pb.ForceRequest(step=step.index, x=x, y=y, n=n, tracks=tracks))
        else:
            angles, thrusts = thrust(speed, course, own)
            action = pb.Action(thrust=pb.ThrustRequest(step=step.index, angles=angles, thrusts=thrusts, tracks=tracks))
        kind = action.WhichOneof("command")
        if args.one_call:
            obs = link.Act(action)  # the command, answered with the next observation
        else:
            {"velocity": link.SetVelocity, "force": link.ApplyForce, "thrust": link.ApplyThrust}[kind](getattr(action, kind))


if __name__ == "__main__":
    sys.exit(main())

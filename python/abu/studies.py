"""Outcome and design studies (docs/model.md §21, §22; docs/python.md): the CLI's `outcomes`
and `design` on the same library calls, with the same checks and messages."""
from . import _abu


def _ramp(ramp):
    return None if ramp is None else [float(v) for v in ramp]


def outcomes(scene, *, ramp=None, t_end=None, samples=256, seed=1, design="sobol", uncertain=(), limit=0.0,
             confidence=0.95, threads=1, rtol=1e-7, every=0.0, method="auto"):
    """What a run-up leaves over sampled starts and uncertain inputs (the CLI's `outcomes`).

    ramp = (omega0, omega1, alpha) [rad/s, rad/s, rad/s^2], else the scene's [simulate] run-up,
    else its constant speed; t_end defaults to the speed change's end + 2 s. uncertain: strings
    'NAME=LOW:HIGH'. Returns a dict: 'summary' (the CLI's outcomes.json), per run 'beta0',
    'inputs', 'outcome', 'residual_q', 'bare_rotor_q', 'balls_fixed_q', 'peak_q',
    'settle_time' (NaN where the run did not settle), 'stalled', 'stuck_off_balance', and 'csv'
    (the CLI's rows). Bad values raise InputError with the CLI's message.
    """
    return _abu.outcomes(scene, _ramp(ramp), None if t_end is None else float(t_end), int(samples), int(seed),
                         str(design), [str(u) for u in uncertain], float(limit), float(confidence), int(threads),
                         float(rtol), float(every), str(method))


def design(scene, vary, *, objective="below", constraints=(), optimize=True, max_evaluations=60, ramp=None,
           t_end=None, samples=64, seed=1, design="sobol", uncertain=(), limit=0.0, threads=1):
    """Which design balances best (the CLI's `design`). vary: strings 'NAME=LOW:HIGH[:LEVELS[:log]]';
    objective 'below', 'median', 'p90', 'worst', 'max:NAME', 'min:NAME'; constraints:
    'stable=W_LO:W_HI', 'capacity=F', 'mass=KG', 'stall=P'. Returns the CLI's design.json as a dict
    ('recommended', 'baseline', 'binding', 'pareto', 'designs', ...) with 'text' (the answer in
    words) and 'csv'.
    """
    return _abu.design(scene, [str(v) for v in vary], str(objective), [str(c) for c in constraints], bool(optimize),
                       int(max_evaluations), _ramp(ramp), None if t_end is None else float(t_end), int(samples),
                       int(seed), str(design), [str(u) for u in uncertain], float(limit), int(threads))

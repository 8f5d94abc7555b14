"""
One seta pressed and pulled off
===============================

The agent model (``ga.Model``, :class:`gecko_agents.model.Model`) runs one short seta of the
paper's Table 1 (L = 5 µm instead of 110 µm, so it takes a second): the plate presses 0.3 µm past
touch-down and pulls straight off (:func:`gecko_agents.protocol.press_pull`). The history's
force against the pressing displacement is drawn by
:func:`gecko_agents.render.force_plots.plot_history`; the run's validity items
(:mod:`gecko_agents.diagnostics`) are printed below it.
"""

import warnings

import matplotlib.pyplot as plt

import gecko_agents as ga
from gecko_agents.render.force_plots import plot_history

params = ga.PAPER_TABLE1.replace(seta={"L": 5.0})
with warnings.catch_warnings():
    warnings.simplefilter("ignore")  # the items are printed below instead
    history = ga.Model(params, n_sim=1, seed=1).run(
        ga.protocol.press_pull(0.3, speed=0.05), progress=False
    )

fig, ax = plt.subplots(figsize=(6.4, 4.4))
plot_history(history, ax=ax)
print(f"peak pull-off {history.peak_pull_off:.4f} µN (Fc = {params.contact.pull_off_force:.4f} µN)")
for name, item in history.meta["validity"]["items"].items():
    verdict = {True: "ok", False: "outside", None: "not judged"}[item["ok"]]
    value = "—" if item["value"] is None else f"{item['value']:.3g}"
    print(f"{name:18s} {value:>8s}  ({item['rule']}) {verdict}")

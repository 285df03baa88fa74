# %% [markdown]
# # ringcontact from Python: a quick start
#
# Notebook-style (cells marked `# %%`: VS Code, Spyder and Jupytext open it as a notebook;
# `python examples/quickstart.py` runs it top to bottom). Units: E* = a = h = 1 unless given.

# %%
import numpy as np
import pandas as pd

import ringcontact as rc

print("ringcontact", rc.__version__)

# %% [markdown]
# ## One state: the spherical concave punch pressed to d = h

# %%
state = rc.solve("sphere", depth=1.0)
print(f"b/a = {state['eps']:.6f}, F/(2 E* h a) = {state['gamma2']:.12f} "
      f"(error estimate {state['error_estimate']:.0e})")

# %% [markdown]
# ## Many states at once: gamma1 and gamma2 of the cone, as a DataFrame

# %%
cone = pd.DataFrame(rc.solve("cone", eps=np.linspace(0.1, 0.9, 9), tolerance=1e-12))
print(cone[["given_eps", "gamma1", "gamma2", "error_estimate"]].to_string(index=False))

# %% [markdown]
# ## Dimensional input: a PDMS half-space under a steel cone dimple (SI units)

# %%
pdms = rc.solve("cone", rim_radius=1e-3, hole_depth=2e-5, youngs_modulus=2e6,
                poisson_ratio=0.49, force=0.05)
print(f"depth {pdms['depth'] * 1e6:.3f} um, contact from b = {pdms['inner_radius'] * 1e3:.4f} mm")

# %% [markdown]
# ## JKR adhesion: pull-off of the cone at d0/h = 0.5

# %%
pulloff = rc.jkr("cone", d0h=0.5)
print("pull-off force under fixed load, F/F0 =", pulloff["fixed_load"]["force"])

# %% [markdown]
# ## Grading another code: the paper's fitted formulas against the converged references

# %%
fits = pd.DataFrame({
    "punch": "flat-annulus",
    "eps": [0.2, 0.5, 0.8],
    # The paper's eq. (3) would go here; a crude guess shows what grading reports.
    "gamma": [0.99, 0.96, 0.85],
})
graded = pd.DataFrame(rc.grade(fits, tol=1e-2)["rows"])
print(graded[["state_value", "value", "reference", "relative_error", "within"]].to_string(index=False))

# %% [markdown]
# ## The reference dataset (the small copy, a few seconds)

# %%
tables = rc.dataset(small=True)
sphere = tables["functions-sphere"]
print(sorted(tables))
print(sphere.attrs["title"])
print(sphere.head(3).to_string(index=False))

"""Symbolic derivation of the rocking deformable cantilever (Vassiliou, Mackie & Stojadinović, 2015).

The physics of the project lives here and nowhere else. From the kinetic and potential energies
of a model description (``models.py``) CasADi derives, by Lagrange's equations, everything the Rust
solver needs; ``ir.py`` turns each CasADi function into a language-neutral instruction list that
``cargo xtask regen`` renders into the ``generated/`` crate.

Modules, in the order the data flows:

* ``shape``     - shape functions psi(eta) and their exact mass moments.
* ``models``    - the model descriptions and the kernel variants (the file model developers edit).
* ``mechanics`` - kinematics, energies, Lagrange's equations, impact maps, derived quantities.
* ``kernels``   - the set of functions every variant exports, as CasADi Functions.
* ``ir``        - CasADi instruction tape -> JSON intermediate form, with golden samples.
* ``errata``    - the paper's printed equations, compared with the derived ones.
"""

__version__ = "0.1.0"

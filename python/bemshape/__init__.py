"""bemshape: local wall thickness, orientation and skeleton of solids given as closed
triangle meshes, by the boundary element method (T. Yamada's shape-feature PDE).

read_mesh(path) -> (V, F); check(V, F) -> dict; thickness(V, F, h0=...) -> dict;
features(V, F, points, h0=...) -> dict. Lengths are in the units of V. Many parts on a
dask.distributed cluster: bemshape.dask.check_parts(paths, min_thickness=...). See
docs/usage.md, section 'Python'.
"""
# The functions and exceptions are those of the compiled module bemshape._core
# (python/bemshape_module.cpp), named here under the package; bemshape.dask is imported on
# demand (it needs dask.distributed, which the rest of the package does not).
from bemshape._core import (
    InputError,
    NumericalError,
    ResourceError,
    __version__,
    check,
    features,
    read_mesh,
    thickness,
)

for _exception in (InputError, NumericalError, ResourceError):
    _exception.__module__ = __name__  # tracebacks say bemshape.InputError, as users name it
del _exception

__all__ = [
    "InputError",
    "NumericalError",
    "ResourceError",
    "check",
    "features",
    "read_mesh",
    "thickness",
]

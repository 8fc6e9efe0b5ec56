# Chooses the backend: the nimbus module when it imports, else the nimbus program.
from . import backend_module, backend_program

_module_backend = None
_program_backends = {}


def choose(mode="AUTO", program_preference=""):
    """The backend for mode AUTO (module, else program), MODULE or PROGRAM; RuntimeError if none."""
    global _module_backend
    if mode in ("AUTO", "MODULE"):
        if _module_backend is None:
            module = backend_module.import_module()
            if module is not None:
                _module_backend = backend_module.ModuleBackend(module)
        if _module_backend is not None:
            return _module_backend
        if mode == "MODULE":
            raise RuntimeError("the nimbus Python module does not import (put its folder on Python's path, "
                               "or choose the program backend in the add-on preferences)")
    program = backend_program.find_program(program_preference)
    if program not in _program_backends:
        _program_backends[program] = backend_program.ProgramBackend(program)
    return _program_backends[program]

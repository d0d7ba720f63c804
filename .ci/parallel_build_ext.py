"""Run a package's `setup.py build_ext` with its C/C++ sources compiled in parallel.

setuptools compiles the sources of one extension one after another; pySCATMECH is one extension
of 80 C++ files. This replaces the compiler's `compile` with the same steps (`_setup_compile`,
`_get_cc_args`, `_compile`, as distutils' own `CCompiler.compile` does them) spread over one
thread per core; the objects and the link are the same. Usage, in the package's folder:
`python3 parallel_build_ext.py` (extra arguments go to `setup.py build_ext`).
"""

import os
import runpy
import sys
from concurrent.futures import ThreadPoolExecutor

import setuptools  # noqa: F401  (installs setuptools' distutils before the import below)
from distutils.ccompiler import CCompiler


def parallel_compile(self, sources, output_dir=None, macros=None, include_dirs=None, debug=0,
                     extra_preargs=None, extra_postargs=None, depends=None):
    macros, objects, extra_postargs, pp_opts, build = self._setup_compile(
        output_dir, macros, include_dirs, sources, depends, extra_postargs)
    cc_args = self._get_cc_args(pp_opts, debug, extra_preargs)

    def one(obj):
        src, ext = build[obj]
        self._compile(obj, src, ext, cc_args, extra_postargs, pp_opts)

    with ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        list(pool.map(one, objects))
    return objects


CCompiler.compile = parallel_compile
sys.argv = ["setup.py", "-q", "build_ext", *sys.argv[1:]]
runpy.run_path("setup.py", run_name="__main__")

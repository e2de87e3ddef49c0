"""The numeric kernels every DCS process that trains pins, read from their one table
(kPinnedKernels in common/pinned_kernels.h), and the programs that train (those marked TORCH
in cmake/layers.cmake), for the deployment checks (check_compose.sh, check_kubernetes.sh): a
deployment starts each such program with those variables, or it starts libtorch twice."""

import re


def pinned_kernels():
    """{name: value} of every pinned variable, in the table's order."""
    with open("common/pinned_kernels.h") as f:
        text = f.read()
    table = re.search(r"kPinnedKernels\[\] = \{\n(.*?)\n\};", text, re.S)
    rows = re.findall(r'^ *\{"([A-Z0-9_]+)", "([^"]*)"\},$', table.group(1) if table else "",
                      re.M)
    if not table or len(rows) != len(table.group(1).splitlines()):
        raise ValueError("common/pinned_kernels.h: kPinnedKernels is not one "
                         '{"NAME", "value"}, a line (tests/deploy/pinned_kernels.py reads it)')
    return dict(rows)


def torch_programs():
    """The DCS programs that link libtorch: cmake/layers.cmake's dcs-* layers marked TORCH."""
    with open("cmake/layers.cmake") as f:
        return set(re.findall(r"^dcs_layer\((dcs-[a-z-]+) [^)]*\bTORCH\b", f.read(), re.M))


def unpinned(environment):
    """The pinned variables `environment` ({name: value}) lacks or sets otherwise, as
    NAME=value."""
    return [f"{name}={value}" for name, value in pinned_kernels().items()
            if str(environment.get(name)) != value]

"""Run PyPI's xacro (2.x) with ``$(find pkg)`` resolved the ROS 1 way.

PyPI's xacro resolves ``$(find pkg)`` through ROS 2's ament index, which a
ROS 1 (catkin / Debian) system does not have.  This module replaces xacro's
find function with one that asks rospkg (``ROS_PACKAGE_PATH``), so
``xacro '$(find arm1)/urdf/arm1.urdf.xacro'`` works as it did on ROS 1.

When rospkg does not know the package, ``arm1`` itself still resolves to this source tree.
"""

import sys

from ..common import packages


def find_package(pkg: str) -> str:
    """The directory of ROS package ``pkg``, as xacro's ``$(find pkg)`` wants it."""
    try:
        return packages.find_package(pkg)
    except LookupError:
        from xacro.substitution_args import SubstitutionException

        raise SubstitutionException("package '%s' not found on ROS_PACKAGE_PATH" % pkg) from None


def install():
    """Make xacro's ``$(find pkg)`` (both the substitution arg and the one
    usable inside ``$(eval ...)``) resolve through :func:`find_package`."""
    from xacro import substitution_args

    substitution_args._eval_find = find_package
    substitution_args._eval_dict['find'] = find_package


def expand(path, mappings=None):
    """Expand the xacro file ``path`` in-process and return the XML text.

    ``mappings`` is a dict of xacro arguments (what ``name:=value`` gives on
    the command line)."""
    import xacro

    install()
    doc = xacro.process_file(path, mappings=dict(mappings or {}))
    return doc.toprettyxml(indent='  ')


def main(argv=None):
    """Command line entry point, same options as ``xacro``."""
    import xacro

    install()
    if argv is not None:
        sys.argv = [sys.argv[0]] + list(argv)
    return xacro.main()


if __name__ == '__main__':
    main()

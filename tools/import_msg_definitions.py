#!/usr/bin/env python3
"""Write a message package's interface (fields, constants, separators) into tools/compat_msgs.

An interface's definition is what its md5sum is made of: field types and names, constants
and the `---` separators. Comments and blank lines do not count, so they are left out.

    tools/import_msg_definitions.py UPSTREAM_PACKAGE_DIR NAME

UPSTREAM_PACKAGE_DIR holds msg/, srv/ and action/ of one release (e.g. a checkout of
moveit_msgs 0.11.4); NAME is the package name under tools/compat_msgs/.
"""

import os
import re
import sys

ARM1 = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFINITIONS = os.path.join(ARM1, 'tools', 'compat_msgs')
STRING_CONSTANT = re.compile(r'^\s*string\s+\w+\s*=')


def interface_lines(text: str) -> list[str]:
    """The lines that make a definition's md5sum, comments and blank lines dropped."""
    out = []
    for line in text.splitlines():
        if line.strip() == '---':
            out.append('---')
            continue
        if not STRING_CONSTANT.match(line):  # a string constant's value may hold a '#'
            line = line.split('#', 1)[0]
        line = ' '.join(line.split())
        if line:
            out.append(line)
    return out


def main() -> int:
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    src, name = sys.argv[1], sys.argv[2]
    for kind in ('msg', 'srv', 'action'):
        folder = os.path.join(src, kind)
        if not os.path.isdir(folder):
            continue
        dest = os.path.join(DEFINITIONS, name, kind)
        os.makedirs(dest, exist_ok=True)
        for fname in sorted(os.listdir(folder)):
            if fname.endswith('.' + kind):
                with open(os.path.join(folder, fname)) as f:
                    lines = interface_lines(f.read())
                with open(os.path.join(dest, fname), 'w') as f:
                    f.write('\n'.join(lines) + '\n')
    return 0


if __name__ == '__main__':
    sys.exit(main())

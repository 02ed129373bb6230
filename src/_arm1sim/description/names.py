"""Names from requests are only names: the rules a model, link or joint name must keep.

They follow SDFormat's (no ``::``, not a reserved ``__…__`` name, not ``world``
for a model) plus what keeps a name printable and bounded. A name is never used
to build a file path; the rules give a clear refusal instead of a surprise.
"""

from __future__ import annotations

import re
import unicodedata


class IllegalName(ValueError):
    """A name breaks a rule; the message names the name (shortened) and the rule."""


# rosgraph.names.is_legal_name's rule without ROS: [~/A-Za-z], then word characters and '/'
_ROS_NAME = re.compile(r'[~/A-Za-z][\w/]*\Z')


def legal_ros_name(name: str) -> bool:
    """A legal ROS graph resource name, as rosgraph.names.is_legal_name ('' is legal)."""
    return name == '' or (_ROS_NAME.match(name) is not None and '//' not in name)


def shown(name: str, width: int = 60) -> str:
    """``name`` as a message may quote it: repr'd and cut to ``width`` characters."""
    text = repr(name)
    return text if len(text) <= width else text[: width - 5] + '...' + text[-2:]


def check_name(name: str, kind: str, max_length: int = 255) -> str:
    """Return ``name`` if it is a legal ``kind`` (model, link, joint) name, else raise."""
    if not isinstance(name, str) or not name:
        raise IllegalName('%s name is empty' % kind)
    if len(name) > max_length:
        raise IllegalName(
            '%s name %s is %d characters long, over the limit of %d (~limits/'
            'name_length)' % (kind, shown(name), len(name), max_length)
        )
    if name != name.strip():
        raise IllegalName('%s name %s starts or ends with white space' % (kind, shown(name)))
    bad = [c for c in name if unicodedata.category(c)[0] == 'C']
    if bad:
        raise IllegalName('%s name %s contains a control character' % (kind, shown(name)))
    if '/' in name or '\\' in name:
        raise IllegalName(
            "%s name %s contains '/' or '\\': a name is not a path" % (kind, shown(name))
        )
    if '::' in name:
        raise IllegalName(
            "%s name %s contains '::', SDFormat's scope separator" % (kind, shown(name))
        )
    if name in ('.', '..'):
        raise IllegalName('%s name %s is not a name' % (kind, shown(name)))
    if name.startswith('__') and name.endswith('__'):
        raise IllegalName(
            '%s name %s is reserved (SDFormat reserves __*__ names)' % (kind, shown(name))
        )
    if kind == 'model' and name == 'world':
        raise IllegalName("model name 'world' is reserved (it names the world frame)")
    return name

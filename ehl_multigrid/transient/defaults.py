"""Defaults of a transient run shared by ``ehl transient`` and the front door."""

#: points along X of a transient run per contact
DEFAULT_POINTS = {"line": 513, "point": 129}
#: inlet X = x/b (point: x/a), upstream enough for a feature to enter the contact
DEFAULT_XMIN = -4.5

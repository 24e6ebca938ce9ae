"""Kinematics of the triad (class III) and the class IV group of order 2."""

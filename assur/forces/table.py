def read_forces(root, chain): pass

"""The jobs: each coursework problem as one result, the answer key of a class, the
coursework's printable programs, many pendulums at once. Above ``numerics``."""

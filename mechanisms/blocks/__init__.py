"""Layer 2: building blocks (dyads) that every mechanism of the book is made of.

Each block takes the motions of its input points (layer 1), returns the motions of its
outputs up to the order asked for, works on whole arrays of crank angles, takes a
``branch`` where there are two solutions, and checks assembly.
"""

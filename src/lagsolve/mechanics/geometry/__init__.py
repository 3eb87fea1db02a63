"""What the sketch of a problem shows, decided from the problem (shapes), with the records it is made of (records) and
the shapes of bodies, curves, forces and links.
"""

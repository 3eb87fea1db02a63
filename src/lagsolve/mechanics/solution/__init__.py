"""What the explicit solve gives beyond q̈ and λ: the normal forces of friction in closed form (normal) and when a
contact sticks (sticking).
"""

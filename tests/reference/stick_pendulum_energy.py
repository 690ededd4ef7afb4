# The stick pendulum of docs/course.md, section 10 (scenes/stick_pendulum.json): a bob of 1 kg on a
# 1 m stick whose other end is pinned at the origin, released horizontal at rest, g = 9.81 m/s².
# Velocityless Verlet as motus runs it, in plain Python:
#   start      p₋₁ = p₀ − v₀h + ½a₀h²           (the Taylor start: second order)
#   step       p' = 2pₙ − pₙ₋₁ + a h², then the projection puts the bob back at 1 m from the pin
#              (the pin does not move, so the bob takes the whole correction)
#   velocity   (pₙ − pₙ₋₁)/h, the backward difference, for the energy ½|v|² + g·y.
# Prints the total energy after 10 s at h = 1/60, 1/120 and 1/240 s.
import math

g, L = 9.81, 1.0
for steps_per_second in (60, 120, 240):
    h = 1 / steps_per_second
    x, y = 1.0, 0.0
    xp, yp = x, y - 0.5 * g * h * h  # v₀ = 0, a₀ = (0, −g)
    for _ in range(10 * steps_per_second):
        xn, yn = 2 * x - xp, 2 * y - yp - g * h * h
        d = math.hypot(xn, yn)
        xn, yn = xn * L / d, yn * L / d
        xp, yp, x, y = x, y, xn, yn
    vx, vy = (x - xp) / h, (y - yp) / h
    print(f"h = 1/{steps_per_second} s: total energy at 10 s {0.5 * (vx * vx + vy * vy) + g * y:.10f} J")

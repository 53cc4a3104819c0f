#!/usr/bin/env python3
"""Writes configs/office_floor.walls: SPEC S4's office experiment, a floor of about 2,000 m² with
repeated rooms. Two east-west corridors 3 m wide, each with a row of ten 5 m x 8 m rooms on either
side (the two middle rows back to back), joined by a north-south corridor 3 m wide at the west end.
Every room has a 1 m door in the middle of its corridor wall. Standard library only."""
import sys

ROOMS, ROOM_W, ROOM_D, CORRIDOR, DOOR = 10, 5.0, 8.0, 3.0, 1.0
X0 = CORRIDOR                      # the rooms start east of the west corridor
X1 = X0 + ROOMS * ROOM_W           # the east wall
# From south to north: rooms, corridor A, rooms, rooms, corridor B, rooms.
Y = [0.0]
for depth in (ROOM_D, CORRIDOR, ROOM_D, ROOM_D, CORRIDOR, ROOM_D):
    Y.append(Y[-1] + depth)
CORRIDORS = [(Y[1], Y[2]), (Y[4], Y[5])]


def wall_with_doors(y, doors):
    """An east-west wall from X0 to X1 at y, open for DOOR metres around each door centre."""
    out, x = [], X0
    for centre in doors:
        out.append((x, y, centre - DOOR / 2, y))
        x = centre + DOOR / 2
    out.append((x, y, X1, y))
    return out


def main():
    walls = [(0.0, 0.0, X1, 0.0), (0.0, Y[-1], X1, Y[-1]), (X1, 0.0, X1, Y[-1])]
    # The west corridor: its outer wall, and its east side closed except at the two corridors.
    walls.append((0.0, 0.0, 0.0, Y[-1]))
    walls += [(X0, 0.0, X0, Y[1]), (X0, Y[2], X0, Y[4]), (X0, Y[5], X0, Y[6])]
    doors = [X0 + (i + 0.5) * ROOM_W for i in range(ROOMS)]
    for y in (Y[1], Y[2], Y[4], Y[5]):   # the corridors' walls, a door per room
        walls += wall_with_doors(y, doors)
    walls.append((X0, Y[3], X1, Y[3]))   # between the back-to-back rooms
    for i in range(1, ROOMS):            # the walls between neighbouring rooms
        x = X0 + i * ROOM_W
        for lo, hi in ((Y[0], Y[1]), (Y[2], Y[3]), (Y[3], Y[4]), (Y[5], Y[6])):
            walls.append((x, lo, x, hi))
    out = sys.stdout
    out.write(f"# SPEC S4's office floor: {X1:.0f} m x {Y[-1]:.0f} m = {X1 * Y[-1]:.0f} m², "
              f"{4 * ROOMS} rooms of {ROOM_W:.0f} m x {ROOM_D:.0f} m\n")
    out.write("# written by scripts/analysis/make_office_floor.py; start: --start 1.5,9.5,0\n")
    for w in walls:
        out.write("{:.2f} {:.2f} {:.2f} {:.2f}\n".format(*w))


if __name__ == "__main__":
    main()

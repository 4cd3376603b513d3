"""Parameter study of the bounce: a ball with restitution e dropped from height H should rise to
e^2 H. The table gives the apex of the first bounce and its error against the time step h."""
import tumble


def apex(h, drop=1.0, e=0.8, radius=0.1):
    world = tumble.World(tumble.WorldDef(time_step=h))
    ground = world.create_body(tumble.BodyDef(type=tumble.BodyType.Static))
    world.create_shape(ground, tumble.ShapeDef(geometry=tumble.HalfSpace(),
                                               material=tumble.Material(restitution=e)))
    ball = world.create_body(tumble.BodyDef(position=[0, 0, drop + radius]))
    world.create_shape(ball, tumble.ShapeDef(geometry=tumble.Sphere(radius=radius),
                                             material=tumble.Material(restitution=e)))
    velocity = world.view("linear_velocities", [ball])
    center = world.view("centers", [ball])
    bounced, top = False, 0.0
    while world.time < 3.0:
        world.step()
        vz = velocity[0, 2]
        bounced = bounced or vz > 0
        if bounced:
            top = max(top, center[0, 2] - radius)
            if vz < 0:
                break
    return top


def table(steps=(1 / 60, 1 / 120, 1 / 240, 1 / 480), drop=1.0, e=0.8):
    rows = []
    for h in steps:
        a = apex(h, drop, e)
        rows.append((h, a, e * e * drop, a - e * e * drop))
    return rows


if __name__ == "__main__":
    print(f"{'h (s)':>10} {'apex (m)':>10} {'e^2 H (m)':>10} {'error (m)':>10}")
    for h, a, expected, error in table():
        print(f"{h:10.5f} {a:10.4f} {expected:10.4f} {error:+10.4f}")

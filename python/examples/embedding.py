"""The README's embedding example, in Python: a spinning box dropped on the ground, drawn at
60 Hz between fixed steps of 1/240 s."""
import tumble


def main(frames=120):
    world = tumble.World(tumble.WorldDef(gravity=[0, 0, -9.81], time_step=1 / 240))

    ground = world.create_body(tumble.BodyDef(type=tumble.BodyType.Static))
    world.create_shape(ground, tumble.ShapeDef(geometry=tumble.HalfSpace()))  # the plane z = 0

    body = world.create_body(tumble.BodyDef(position=[0, 0, 2],  # m
                                            angular_velocity=[0, 3, 0]))  # rad/s, world frame
    cube = tumble.ShapeDef(geometry=tumble.Box(half_extents=[0.5, 0.5, 0.5]))  # m
    cube.material.density = 500  # kg/m^3: the body's mass comes from it
    world.create_shape(body, cube)

    heights = []
    for _ in range(frames):  # a 60 Hz render loop
        r = world.advance(1 / 60)  # whole fixed steps
        pose = world.interpolated_transform(body, r.fraction)
        heights.append(pose.position[2])  # draw the body here
    return heights


if __name__ == "__main__":
    for z in main():
        print(f"{z:.3f} m")

"""What a robot model folder says about its robot, beside the URDF: :mod:`lazyground.robots.defaults`."""

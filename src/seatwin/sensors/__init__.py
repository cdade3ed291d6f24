"""Sensor models: the lidar (``lidar``, its config, physics and range models), the depth-buffer
range model, radar; each module imports only what it needs."""

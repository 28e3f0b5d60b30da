"""Nav2 around NavFn: the ``NavfnPlanner`` plugin, its parameters, and the global costmap
(static and inflation layers) it plans on, each as the Nav2 code computes it."""

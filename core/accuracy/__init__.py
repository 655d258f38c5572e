"""What accuracy costs in time: sweeps of each accuracy knob against a reference render.

This package sits beside the lecture's two halves and may use both
(:mod:`core.object_order` and :mod:`core.image_order`); they never use it.

- :mod:`.supersampling`: N x N stratified jittered samples per pixel, and
  Whitted's adaptive supersampling;
- :mod:`.tessellation`, :mod:`.resolution`: the other knobs the pipelines lack;
- :mod:`.visible_surface`: which object each pixel centre sees;
- :mod:`.reference`: the render everything is compared with;
- :mod:`.error_metrics`: RMSE, FLIP, wrong visible objects, depth error;
- :mod:`.sweep`: the knobs, the timed sweeps and their knees;
- :mod:`.explanations`: why each curve has its shape, in a sentence or two;
- :mod:`.cost_plot` and :mod:`.cost_files`: the plot and the files a sweep writes.
"""

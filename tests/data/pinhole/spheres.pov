#version 3.7;
global_settings { assumed_gamma 1 max_trace_level 5 ambient_light rgb 0.353553 }
background { rgb <0.1,0.2,0.4> }
camera { perspective location <0,-6,2.5> sky <0,0,1> up y right -x look_at <0,0,0.6> angle 40 }
light_source { <4,-4,6> rgb 0.353553 }
light_source { <-5,-3,4> rgb 0.353553 }
sphere { <0,0,1>, 1 texture { pigment { rgb <0.9,0.3,0.2> transmit 0 } finish { ambient 0.8 diffuse 0.8 phong 0 phong_size 1 reflection 0 } } }
sphere { <-1.9,0.8,0.7>, 0.7 texture { pigment { rgb <0.2,0.7,0.3> transmit 0 } finish { ambient 0.7 diffuse 0.7 phong 0.2 phong_size 12 reflection 0.2 } } }
sphere { <1.8,0.5,0.6>, 0.6 texture { pigment { rgb <0.9,0.8,0.3> transmit 0 } finish { ambient 1 diffuse 1 phong 0 phong_size 1 reflection 0 } } }
mesh { triangle { <-6,-6,0>, <6,-6,0>, <6,6,0> } triangle { <-6,-6,0>, <6,6,0>, <-6,6,0> } texture { pigment { rgb <0.7,0.7,0.7> transmit 0 } finish { ambient 1 diffuse 1 phong 0 phong_size 1 reflection 0 } } }

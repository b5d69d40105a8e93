# Helical flow (thesis §4.3): an auger (a cylinder with a helical ramp) turning at 95 rpm in a box
# of 28,800 spheres lifts them.
#   make -f Makefile.cases helical-flow   fill and settle the box around the still auger, turn it
#                                         for the thesis's 2.9 s, report the flow rate up the ramp,
#                                         the drive torque and power, and plot them
#                                         (workflows/helical-flow/README.md: choices, cost, results)
HEL_DIR := $(OUT)/helical-flow
HEL_SCENE := workflows/helical-flow/scene.toml
HEL_REPORT := scripts/helical_flow_report.py
# The geometry of the scene's auger, for the report: shaft and flight radii, pitch [m], speed, and
# the counting plane (0.4 m: mid-depth of the settled bed, a turn above the flight's lowest edge).
HEL_GEOMETRY := --walls shaft,cap,ramp --rpm -95 --r-in 0.1 --r-out 0.3 --pitch 0.3 --plane 0.4

$(HEL_DIR)/settled.h5: $(HEL_SCENE) $(BIN)/gen-primary
	$(BIN)/gen-primary --scene $(HEL_SCENE) --out $@

# One VTK frame every 0.02 s (velocity, displacement); every wall's force and torque every 100
# steps; the energy log every 0.01 s (the scene's energy_every: the drive's work against what is
# dissipated and the potential energy gained).
$(HEL_DIR)/spun.h5 $(HEL_DIR)/walls.csv $(HEL_DIR)/spun.energy.csv $(HEL_DIR)/vtk/spin_particles.pvd &: $(HEL_SCENE) $(HEL_DIR)/settled.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(HEL_SCENE) --stage spin --in $(HEL_DIR)/settled.h5 --out $(HEL_DIR)/spun.h5 \
	  --vtk $(HEL_DIR)/vtk --wall-forces $(HEL_DIR)/walls.csv --wall-forces-every 100 \
	  --checkpoint-every 100000 --restart

HEL_PLOTS := $(HEL_DIR)/helical.png $(HEL_DIR)/flow.csv $(HEL_DIR)/power.csv $(HEL_DIR)/summary.csv
$(HEL_PLOTS) &: $(HEL_DIR)/settled.h5 $(HEL_DIR)/spun.h5 $(HEL_DIR)/walls.csv $(HEL_DIR)/vtk/spin_particles.pvd \
    $(HEL_REPORT) scripts/plane_flux.py scripts/post_table.py
	$(PYTHON) $(HEL_REPORT) --start $(HEL_DIR)/settled.h5 --end $(HEL_DIR)/spun.h5 \
	  --frames $(HEL_DIR)/vtk/spin_particles.pvd --wall-forces $(HEL_DIR)/walls.csv $(HEL_GEOMETRY) --skip 0.5 \
	  --flux $(HEL_DIR)/flow.csv --power $(HEL_DIR)/power.csv --summary $(HEL_DIR)/summary.csv --png $(HEL_DIR)/helical.png

# The power balance: the drive's work into potential energy, friction and damping.
$(HEL_DIR)/energy.png: $(HEL_DIR)/spun.energy.csv scripts/plot_energy.py scripts/run_log_figure.py scripts/post_table.py
	$(PYTHON) scripts/plot_energy.py $< $@

# Three instants coloured by speed [0, 1 m/s] (the flight's edge moves at 3 m/s, the lifted bed at
# a few cm/s): in perspective, and cut by the plane y = 0 through the axis, seen from +y.
HEL_TIMES := 0.5 1.5 2.9
HEL_RENDER := xvfb-run -a $(BIN)/dem-render --quiet --relative-time --range 0,1 --box -0.5,-0.5,0.0,0.5,0.5,1.0 --size 1024,768
HEL_PNGS := $(foreach t,$(HEL_TIMES),$(HEL_DIR)/render/perspective_$(t).png $(HEL_DIR)/render/cut_$(t).png)
HEL_CUT := --point 0,0,0.5 --normal 0,1,0
$(eval $(call render_rules,$(HEL_DIR),$(HEL_DIR)/vtk/spin_particles.pvd,HEL_RENDER,HEL_CUT))

.PHONY: helical-flow helical-flow-outputs
helical-flow: build
	@$(MAKE) --no-print-directory -f $(SELF) helical-flow-outputs
	@echo "helical-flow: VTK series $(HEL_DIR)/vtk/spin_particles.pvd (velocity), walls vtk/spin_walls.pvd"
	@echo "helical-flow: plot $(HEL_DIR)/helical.png, flow rate $(HEL_DIR)/flow.csv, torque and power $(HEL_DIR)/power.csv, figures $(HEL_DIR)/summary.csv"
	@echo "helical-flow: power balance $(HEL_DIR)/spun.energy.csv and energy.png, renders $(HEL_DIR)/render/*.png"
helical-flow-outputs: $(HEL_PLOTS) $(HEL_DIR)/energy.png $(HEL_PNGS)
CASES += helical-flow

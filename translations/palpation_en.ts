<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="en_US">
<context>
    <name>DevicePanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="51"/>
        <source>Thumb</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="51"/>
        <source>Index</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="52"/>
        <source>Middle</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="52"/>
        <source>Ring</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="53"/>
        <source>Little</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ForcePlots</name>
    <message>
        <location filename="../ui/force_plots.cpp" line="26"/>
        <source>thumb</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="26"/>
        <source>index</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="27"/>
        <source>middle</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="27"/>
        <source>ring</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="28"/>
        <source>little</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ReviewWindow</name>
    <message>
        <location filename="../ui/review_window.cpp" line="34"/>
        <source>thumb</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="34"/>
        <source>index</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="35"/>
        <source>middle</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="35"/>
        <source>ring</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="36"/>
        <source>little</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::DevicePanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="442"/>
        <source>Simulated HandHIRO (scripted palpation)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="443"/>
        <source>Mouse palpation (no robot)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="444"/>
        <source>Device</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="445"/>
        <source>HandHIRO address</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="446"/>
        <source>Loop jitter</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="447"/>
        <source>The HandHIRO network link is chosen at start: palpation-trainer --device emulator, or --device handhiro --robot ADDRESS:PORT.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="460"/>
        <source>attached</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="460"/>
        <source>released</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="462"/>
        <source>%1 us (max over 0.5 s)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::EventText</name>
    <message>
        <location filename="../ui/event_text.cpp" line="21"/>
        <source>Patient&apos;s tumour</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="23"/>
        <source>%1 at (%2, %3, %4) cm, %5 kPa</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="24"/>
        <source>Sphere</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="24"/>
        <source>Ellipsoid</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="26"/>
        <source>Painted tumour %1, %2 kPa</source>
        <translation type="unfinished"></translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/event_text.cpp" line="31"/>
        <source>%1 (%n elements)</source>
        <translation>
            <numerusform>%1 (%n element)</numerusform>
            <numerusform>%1 (%n elements)</numerusform>
        </translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="36"/>
        <source>Add tumour: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="37"/>
        <source>Remove tumour: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="38"/>
        <source>Erase</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="38"/>
        <source>Paint</source>
        <translation type="unfinished"></translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/event_text.cpp" line="40"/>
        <source>Erase stroke (%n elements)</source>
        <translation>
            <numerusform>Erase stroke (%n element)</numerusform>
            <numerusform>Erase stroke (%n elements)</numerusform>
        </translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/event_text.cpp" line="40"/>
        <source>Paint stroke (%n elements)</source>
        <translation>
            <numerusform>Paint stroke (%n element)</numerusform>
            <numerusform>Paint stroke (%n elements)</numerusform>
        </translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="43"/>
        <source>Undo: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="48"/>
        <source>loading patient: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="50"/>
        <source>patient loaded: %1 nodes, %2 tetrahedra, backend %3</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="51"/>
        <source>patient not loaded: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="52"/>
        <source>solver/contact parameters changed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="56"/>
        <source>device: mouse palpation</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="57"/>
        <source>device: scripted hand</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="58"/>
        <source>trainee mode</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="59"/>
        <source>instructor mode</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="60"/>
        <source>guided practice (trainee)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="61"/>
        <source>exam (trainee)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="65"/>
        <source>trainee mark %1 at (%2, %3, %4) cm</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="68"/>
        <source>trainee mark %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="69"/>
        <source>, %1 % confident</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="70"/>
        <source>: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="73"/>
        <source>guided practice ended</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="73"/>
        <source>exam ended</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="74"/>
        <source>backend error: %1; continuing on the CPU from rest (forces held, then blended)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="75"/>
        <source>simulation diverged (%1): body reset to rest (forces held, then blended)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="77"/>
        <source>simulation stopped: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="86"/>
        <source>small</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="87"/>
        <source>medium</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="88"/>
        <source>large</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="89"/>
        <source>wide and flat</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="90"/>
        <source>narrow and projecting</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="93"/>
        <source>Healthy breast, %1 (%2 mL), the paper&apos;s size, no tumour</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="94"/>
        <source>Healthy breast, %1 (%2 mL), no tumour</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="96"/>
        <source>The paper&apos;s case: medium breast, tumour 3 cm diameter, 107 kPa, centre 2.0 cm below the skin</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="98"/>
        <source>soft</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="98"/>
        <source>hard</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="98"/>
        <source>firm</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="99"/>
        <source>Medium breast, %1 tumour %2 cm diameter (%3 kPa), centre %4 cm below the skin</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::ForcePlots</name>
    <message>
        <location filename="../ui/force_plots.cpp" line="107"/>
        <source>Export plot as PNG</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="107"/>
        <source>PNG images (*.png)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="111"/>
        <source>Export forces as CSV</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="111"/>
        <source>CSV files (*.csv)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="118"/>
        <source>|F| vs time</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="119"/>
        <source>Fz vs time</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="120"/>
        <source>Fz vs x (Fig. 6)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="121"/>
        <source>solid: sent to the device (limit %1 N, dotted); dashed: simulated contact force</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="122"/>
        <source>Force magnitude per finger (N)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="123"/>
        <source>Fz per finger (N)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="124"/>
        <source>Fz (N) against finger x (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="130"/>
        <source>%1 (simulated)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="135"/>
        <location filename="../ui/force_plots.cpp" line="136"/>
        <source>device limit</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="137"/>
        <source>Resume</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="137"/>
        <source>Pause</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="138"/>
        <source>Export PNG...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="139"/>
        <source>Export CSV...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="141"/>
        <source>The device renders the simulated force times the force scale, chosen when the patient loads: a deep press (%1 % of the tissue thickness) over the stiffest part of the patient maps to %2 % of the device&apos;s limit, so that the tumour&apos;s extra force stays within the device&apos;s range. Device limit %3 N = %4 N simulated. Solid lines: sent (device units); dashed: simulated.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="157"/>
        <source>Force scale %1 (device configuration): %2 N simulated -&gt; %3 N at the device</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="162"/>
        <source>Force scale %1: deep press %2 N simulated -&gt; %3 N at the device (limit %4 N)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="167"/>
        <source>Force scale 1: simulated forces sent unscaled</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::ImportDialog</name>
    <message>
        <location filename="../ui/import_dialog.cpp" line="98"/>
        <source>Scanned breast surface</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="99"/>
        <source>Surface meshes (*.stl *.obj *.ply);;All files (*)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="109"/>
        <source>Cancelling...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="124"/>
        <source>Import a scanned breast</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="130"/>
        <source>Patient name</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="131"/>
        <source>Resolution</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="132"/>
        <source>File units</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="133"/>
        <source>Chest-wall plane</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="137"/>
        <source>Scan file</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="138"/>
        <source>n (into the chest), d (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="143"/>
        <source>Browse...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="144"/>
        <source>Coarse (real time on a CPU)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="145"/>
        <source>Paper (GPU)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="146"/>
        <source>Fine (GPU)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="147"/>
        <source>metres</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="148"/>
        <source>centimetres</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="149"/>
        <source>millimetres</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="150"/>
        <source>Find automatically (the largest flat region)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="151"/>
        <source>Untick to give the plane n . x = d by hand: n points out of the body into the chest.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="152"/>
        <source>Import</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="153"/>
        <source>Cancel import</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="154"/>
        <source>Save as patient</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="155"/>
        <source>Close</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="181"/>
        <source>Choose a scan file (STL, OBJ or PLY) first.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="190"/>
        <source>The base plane&apos;s normal must not be zero.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="205"/>
        <source>Reading %1...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="220"/>
        <source>Cancelled: nothing was saved.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="226"/>
        <source>Import failed: nothing was saved.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="231"/>
        <source>Done in %1 s (meshing %2 s).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="235"/>
        <source>%1 nodes, %2 tetrahedra. Repairs: %3. Chest wall (fixed) %4: n = (%5, %6, %7), %8 cm², %9 % of the body&apos;s outline, tilted %10° from the scan&apos;s z axis.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="239"/>
        <source>none</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="240"/>
        <source>found</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="240"/>
        <source>given</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="251"/>
        <source>No patient library is open.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="259"/>
        <source>Give the patient a name.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="264"/>
        <source>A patient named &quot;%1&quot; exists already in %2: choose another name.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="275"/>
        <source>Saved as &quot;%1&quot; in the patient library.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::MainWindow</name>
    <message>
        <location filename="../ui/main_window.cpp" line="160"/>
        <source>Mouse palpation: move over the breast; the wheel or a downward drag presses the fingertip in.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="170"/>
        <source>No element lies inside that shape: nothing added.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="220"/>
        <source>Stored pressure levels not used (defaults apply): %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="260"/>
        <source>This session is not recorded: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="262"/>
        <source>Recovered interrupted recordings: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="264"/>
        <source>Patient library not available (built-in phantoms only): %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="304"/>
        <source>no patient library is open: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="340"/>
        <source>No fingertip on the breast: nothing marked.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="340"/>
        <source>This session is not recorded: nothing marked.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="382"/>
        <source>Patient &quot;%1&quot; saved; choose it and Load patient to palpate it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="395"/>
        <source>Open a session recording</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="396"/>
        <source>Session recordings (*.palrec *.prec);;All files (*)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="399"/>
        <source>Cannot open the recording</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="403"/>
        <source>Save screenshot</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="403"/>
        <source>PNG images (*.png)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="433"/>
        <location filename="../ui/main_window.cpp" line="620"/>
        <source>Stereo</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="443"/>
        <source>Eye separation</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="443"/>
        <source>Eye angle (degrees):</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="522"/>
        <source>End the exam now? No more marks can be made after it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="541"/>
        <location filename="../ui/main_window.cpp" line="550"/>
        <location filename="../ui/main_window.cpp" line="555"/>
        <location filename="../ui/main_window.cpp" line="650"/>
        <source>Curriculum</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="547"/>
        <source>Open a curriculum</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="547"/>
        <source>Curricula (*.json)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="606"/>
        <source>Palpation Trainer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="607"/>
        <source>&amp;File</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="608"/>
        <source>&amp;Open recording...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="609"/>
        <source>Mark lump here (M)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="610"/>
        <source>Trainee: &quot;I feel a lump here&quot;: marks the index fingertip&apos;s position in the recording</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="611"/>
        <source>Save &amp;screenshot...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="612"/>
        <source>&amp;Quit</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="613"/>
        <source>&amp;Edit</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="614"/>
        <source>Undo</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="615"/>
        <source>Redo</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="616"/>
        <source>&amp;View</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="617"/>
        <source>Camera</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="618"/>
        <source>Oblique</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="618"/>
        <source>Top</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="618"/>
        <source>Side</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="618"/>
        <source>Front</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="621"/>
        <source>Mono</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="621"/>
        <source>Anaglyph (red/cyan)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="621"/>
        <source>Side by side</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="621"/>
        <source>Interlaced</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="621"/>
        <source>Quad-buffer (shutter glasses)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="623"/>
        <source>Eye separation...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="624"/>
        <source>Mirrored (half-mirror display)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="625"/>
        <source>Fast rendering (software OpenGL)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="626"/>
        <source>A lighter 3-D view: plain background, no highlights on the skin, an unlit chest. On by itself when the computer draws OpenGL in software.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="628"/>
        <source>Displacement colour map</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="629"/>
        <source>Stress colour map (von Mises)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="630"/>
        <source>Show tumours</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="631"/>
        <source>Panels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="632"/>
        <source>&amp;Mode</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="633"/>
        <source>Instructor mode</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="642"/>
        <source>Coverage overlay</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="643"/>
        <source>Colours the skin by the highest pressure reached: yellow light, orange medium, red deep. Not shown in an exam.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="645"/>
        <source>Clear coverage</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="646"/>
        <source>Trainee progress...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="647"/>
        <source>Each trainee&apos;s exams over time and the class&apos;s results</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="648"/>
        <source>Pressure levels...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="649"/>
        <source>What counts as light, medium and deep pressure in the coverage and the score</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="651"/>
        <source>Open curriculum file...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="652"/>
        <source>No curriculum (free exams)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="653"/>
        <source>Next curriculum case</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="654"/>
        <source>Loads the trainee&apos;s first case of the curriculum not yet passed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="658"/>
        <source>Tools</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="659"/>
        <source>Coverage</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="660"/>
        <source>Camera / scripted hand</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="661"/>
        <source>Palpate with the mouse</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="735"/>
        <source>Trainee</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="736"/>
        <source>Who is the trainee? Choose a name or type a new one (empty: anonymous, no result stored).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="754"/>
        <source>Trainee not added to the library: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="765"/>
        <source>Patient library not available: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="802"/>
        <source>The exam&apos;s result is kept on this station: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="805"/>
        <source>The exam&apos;s result is not stored: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="837"/>
        <source>Pressure levels set: they apply to the exams that start from now on.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="869"/>
        <source>No curriculum is chosen (Mode &gt; Curriculum).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="877"/>
        <source>The trainee&apos;s results could not be read: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="882"/>
        <source>%1 has passed every case of %2.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="923"/>
        <source>Curriculum %1: case %2 of %3</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="924"/>
        <source>Curriculum %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="942"/>
        <source>Coverage: %1 none %2 light %3 %4 medium %5 %6 deep %7</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1030"/>
        <source>, trainee %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1105"/>
        <source>Not recording</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1106"/>
        <source>Recording stopped: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1107"/>
        <source>Recording (%1 marks)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="144"/>
        <location filename="../ui/main_window.cpp" line="662"/>
        <source>Patient</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="334"/>
        <source>The exam has ended: nothing marked.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="349"/>
        <source>Mark %1: &quot;I feel a lump here&quot; at (%2, %3, %4) cm, %5 % confident, recorded.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="634"/>
        <source>The instructor&apos;s view: every panel, the answer included. From a trainee mode it asks for a confirmation.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="636"/>
        <source>Guided practice</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="637"/>
        <source>Trainee: palpate and mark; the instructor&apos;s panels are hidden.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="638"/>
        <source>Exam</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="639"/>
        <source>Trainee examined: palpate and mark; the answer stays hidden until the exam ends.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="640"/>
        <source>End exam</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="641"/>
        <source>Stops the exam: no more marks.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="655"/>
        <source>Possible (25 %)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="655"/>
        <source>Likely (50 %)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="655"/>
        <source>Probable (75 %)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="655"/>
        <source>Certain (100 %)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="657"/>
        <source>How sure you are of the next mark</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="663"/>
        <source>Tumours</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="664"/>
        <source>Forces</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="665"/>
        <source>Simulation</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="666"/>
        <source>Device</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="705"/>
        <source>Return to instructor mode? This ends the trainee&apos;s session and shows the answer, the patient&apos;s details and every panel. For the instructor only.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="707"/>
        <source>Leave the exam? This ends it: no more marks can be made in it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="708"/>
        <source>Change of mode</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1032"/>
        <source>Instructor: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1034"/>
        <source>Guided practice: case %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1034"/>
        <source>Guided practice ended: case %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1035"/>
        <source>Exam: case %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1035"/>
        <source>Exam ended: case %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1049"/>
        <source>%1 nodes, %2 tetrahedra</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1095"/>
        <source>Backend: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1095"/>
        <source>Backend: %1 (fallback)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1097"/>
        <source>Simulation: %1 Hz</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1098"/>
        <source>Haptic: %1 Hz</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1100"/>
        <source>mouse</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1101"/>
        <source>simulated HandHIRO</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1102"/>
        <source>Device: %1, %2</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1102"/>
        <source>connected</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1102"/>
        <source>not connected</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1103"/>
        <source>View: %1 fps</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::PatientPanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="123"/>
        <source>Breast phantom (paper&apos;s tumour)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="124"/>
        <source>Box phantom</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="125"/>
        <source>The paper&apos;s breast with its tumour (107 kPa at x = 12.5 cm).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="126"/>
        <source>A 10 x 10 x 5 cm block of tissue, no tumour.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="133"/>
        <source>Coarse (about 1,000 nodes, real time on a CPU)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="134"/>
        <source>Paper (about 9,100 nodes, GPU)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="135"/>
        <source>Fine (GPU)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="136"/>
        <source>Patient</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="137"/>
        <source>Resolution</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="138"/>
        <source>Tissue Young&apos;s modulus</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="139"/>
        <source>Poisson ratio</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="140"/>
        <source>Load patient</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="141"/>
        <source>Import scan...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="142"/>
        <source>Patients from the library (built-in shapes, graded tumour cases, imported scans) and the built-in phantoms.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="143"/>
        <source>Phantom patients only; an imported scan keeps the resolution it was meshed at.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::PressureDialog</name>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="16"/>
        <source>Pressure levels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="17"/>
        <source>A touch counts at a level when the fingertip pad presses the skin in by this share of the tissue&apos;s thickness under it, or presses with this force, whichever comes first. They apply to the exams that start from now on.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="22"/>
        <source>Indentation (% of thickness)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="23"/>
        <source>Force (N)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="24"/>
        <source>Light</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="24"/>
        <source>Medium</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="24"/>
        <source>Deep</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="46"/>
        <source>OK</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="47"/>
        <source>Cancel</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="48"/>
        <source>Restore defaults</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="86"/>
        <source>Each level must be above the one before it, in indentation and in force, and deep indentation below 100 %.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::ProgressWindow</name>
    <message>
        <location filename="../ui/progress_window.cpp" line="83"/>
        <source>Trainee progress</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <source>Date</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <source>Case</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <location filename="../ui/progress_window.cpp" line="194"/>
        <source>Sensitivity</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <location filename="../ui/progress_window.cpp" line="195"/>
        <source>False positives</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <location filename="../ui/progress_window.cpp" line="197"/>
        <source>Light</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <location filename="../ui/progress_window.cpp" line="197"/>
        <source>Medium</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <location filename="../ui/progress_window.cpp" line="197"/>
        <source>Deep</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="90"/>
        <source>Deep over tumours</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="90"/>
        <source>Exam time (s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="90"/>
        <location filename="../ui/progress_window.cpp" line="113"/>
        <source>Passed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="106"/>
        <source>Trainee:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="111"/>
        <location filename="../ui/progress_window.cpp" line="113"/>
        <source>Trainee</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="113"/>
        <source>Exams</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="113"/>
        <source>Latest</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="113"/>
        <source>Latest sensitivity</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="113"/>
        <source>Latest false positives</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="114"/>
        <source>Latest deep coverage</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="114"/>
        <source>Best</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="114"/>
        <source>Best sensitivity</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="114"/>
        <source>Best false positives</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="115"/>
        <source>Best deep coverage</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="117"/>
        <source>Class</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="147"/>
        <source>No patient library is open: no trainees.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="191"/>
        <source>yes</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="191"/>
        <source>no</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="196"/>
        <source>Coverage</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="199"/>
        <source>Exam time</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::ReviewWindow</name>
    <message>
        <location filename="../ui/review_window.cpp" line="220"/>
        <source>Export the session as CSV</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="220"/>
        <source>CSV files (*.csv)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="222"/>
        <source>Export CSV</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="226"/>
        <source>Folder for the exam report</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="230"/>
        <source>Save report</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="231"/>
        <source>Report written to %1 (%2)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="234"/>
        <source>Folder for the PNG frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/review_window.cpp" line="237"/>
        <source>%n frame(s) written to %1</source>
        <translation>
            <numerusform>%n frame written to %1</numerusform>
            <numerusform>%n frames written to %1</numerusform>
        </translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="280"/>
        <source>Review: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="281"/>
        <location filename="../ui/review_window.cpp" line="339"/>
        <source>Pause</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="281"/>
        <location filename="../ui/review_window.cpp" line="339"/>
        <location filename="../ui/review_window.cpp" line="348"/>
        <source>Play</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="282"/>
        <source>Speed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="283"/>
        <source>Export CSV...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="284"/>
        <source>Export PNG frames...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="285"/>
        <source>Instructor events and trainee marks (click to go there)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="286"/>
        <source>&lt;b&gt;Exam score&lt;/b&gt;</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="287"/>
        <source>Coverage</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="288"/>
        <source>The skin coloured by the highest pressure reached: grey none, yellow light, orange medium, red deep</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="289"/>
        <source>Save report...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="291"/>
        <source>Scoring the exam...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="300"/>
        <source>Force on each fingertip (N): sent to the device (solid), re-simulated simulation force (dashed)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="301"/>
        <source>Force on each fingertip (N): recorded (solid), re-simulated (dashed)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="305"/>
        <source>%1 (re-sim.)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="307"/>
        <source>now</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="308"/>
        <source>Events</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="369"/>
        <location filename="../ui/review_window.cpp" line="408"/>
        <source>No score: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="374"/>
        <source>Tumours found: %1 of %2</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="375"/>
        <source>False positives: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="376"/>
        <source>Coverage: light %1, medium %2, deep %3</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="378"/>
        <source>Vertical strips: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="398"/>
        <source>Coverage up to %1: light %2, medium %3, deep %4</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="409"/>
        <source>The exam is still being scored.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="472"/>
        <source>Re-simulation stopped: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="475"/>
        <source>Re-simulated %1 of %2 simulation steps (backend %3). Largest difference from the recorded simulation forces: %4 N (%5 finger at %6 s; largest recorded force %7 N).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="484"/>
        <source>Re-simulated %1 of %2 simulation steps (backend %3). Largest difference from the recorded simulation forces: 0 N (largest recorded force %4 N).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="491"/>
        <source>Reproduced: same backend and settings give the same forces.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="492"/>
        <source>Not reproduced exactly (another backend or settings).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="494"/>
        <source>The forces sent at 1 kHz differ from the simulation&apos;s by up to %1 N (the haptic loop&apos;s local contact model, coupling and safety filter).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="498"/>
        <source>Re-simulated %1 of %2 ticks (backend %3) from the recorded device input at the scenario&apos;s time step. Largest difference from the recorded forces: %4 N (largest recorded force %5 N).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="507"/>
        <source>The recording was interrupted: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="508"/>
        <source>The recording was recovered after an interruption.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="515"/>
        <source>Written: %1</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::ScoreDialog</name>
    <message>
        <location filename="../ui/score_dialog.cpp" line="29"/>
        <source>Cover the whole breast at light pressure: %1% of the skin was reached at that level.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="30"/>
        <source>Cover the whole breast at medium pressure: %1% of the skin was reached at that level.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="31"/>
        <source>Cover the whole breast at deep pressure: %1% of the skin was reached at that level.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="36"/>
        <source>Search in vertical strips, head to foot, overlapping each by about a third of a finger pad: %1 strips covered %2% of the path.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="40"/>
        <source>Overlap neighbouring strips: they left gaps between them.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="42"/>
        <source>Press deep at every spot: a lump %1 mm below the skin was missed where deep pressure was not reached.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="44"/>
        <source>Check a suspected lump at all three pressure levels before marking it: %1 mark(s) found no lump.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="45"/>
        <source>A complete examination: keep this pattern and pressure.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="51"/>
        <source>tumours found</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="52"/>
        <source>false positives</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="53"/>
        <source>light coverage</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="54"/>
        <source>medium coverage</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="55"/>
        <source>deep coverage</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="56"/>
        <source>deep pressure over each tumour</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="57"/>
        <source>exam time</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="65"/>
        <source>Exam score</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="72"/>
        <source>Curriculum case:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="73"/>
        <source>passed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="73"/>
        <source>not passed: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="79"/>
        <source>Tumours found:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="79"/>
        <source>%1 of %2</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="80"/>
        <source>False positives:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="81"/>
        <source>Sensitivity:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="82"/>
        <source>Positive predictive value:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="83"/>
        <source>Position error:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="84"/>
        <source>%1 mm (mean over the tumours found)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="85"/>
        <source>Exam time:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="85"/>
        <source>%1 s</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="86"/>
        <source>Coverage:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="87"/>
        <source>light %1, medium %2, deep %3</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="89"/>
        <source>Vertical strips:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="92"/>
        <source>tumour %1: %2</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="92"/>
        <source>yes</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="92"/>
        <source>no</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="93"/>
        <source>Deep pressure over each tumour:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="96"/>
        <source>Advice:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="106"/>
        <source>Skin from above: grey not pressed, yellow light, orange medium, red deep; circles: the tumours (green: found); marks: green correct, red false</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="110"/>
        <source>Save report...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="113"/>
        <source>Close</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="117"/>
        <source>Save the exam report into</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="121"/>
        <source>Save report</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::SimulationPanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="350"/>
        <source>Backend</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="351"/>
        <source>CG tolerance</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="352"/>
        <source>CG max. iterations</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="353"/>
        <source>Force error held</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="354"/>
        <source>off: fixed CG tolerance</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="355"/>
        <source>The finger-force error the solver holds, in percent of the converged force: it picks the loosest CG tolerance that keeps it, starting from the one above, and checks it against a converged step every so often. Off: the CG tolerance stays as set.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="358"/>
        <source>State</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="359"/>
        <source>Safety</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="360"/>
        <source>Step time</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="361"/>
        <source>CG iterations</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="362"/>
        <source>Simulation rate</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="363"/>
        <source>Tissue pace</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="364"/>
        <source>Simulated time a wall-clock second. Below 100 % this patient&apos;s mesh is too fine for this machine to keep real time: the tissue moves in slow motion, and the solver&apos;s time step is the shortest that keeps %1 % of the pace the longest one would.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="368"/>
        <source>Haptic rate</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="369"/>
        <source>Apply solver settings</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="370"/>
        <source>A backend change takes effect when the patient is (re)loaded.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="383"/>
        <source>stopped</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="384"/>
        <source>loading</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="385"/>
        <source>running</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="386"/>
        <source>swapping</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="387"/>
        <source>error: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="392"/>
        <source>no fault</source>
        <translation type="unfinished"></translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/panels.cpp" line="393"/>
        <source>%n backend fallback(s)</source>
        <translation>
            <numerusform>%n backend fallback</numerusform>
            <numerusform>%n backend fallbacks</numerusform>
        </translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/panels.cpp" line="394"/>
        <source>%n divergence reset(s)</source>
        <translation>
            <numerusform>%n divergence reset</numerusform>
            <numerusform>%n divergence resets</numerusform>
        </translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="395"/>
        <source>forces held and blended</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="399"/>
        <source>%1 ms</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="401"/>
        <location filename="../ui/panels.cpp" line="407"/>
        <source>%1 Hz</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="405"/>
        <source>%1 % of real time, dt %2 ms</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::TumourEditor</name>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="13"/>
        <source>Tumour (paper, 107 kPa)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="13"/>
        <source>Ueda et al., paper section 4.1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="14"/>
        <source>Invasive ductal carcinoma (Krouskop, 5%)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="14"/>
        <source>Krouskop et al. 1998: 93-112 kPa at 5% precompression</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="15"/>
        <source>Invasive ductal carcinoma (Krouskop, 20%)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="15"/>
        <source>Krouskop et al. 1998: 460-558 kPa at 20% precompression</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="16"/>
        <source>Fibrous tissue (Krouskop, 5%)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="16"/>
        <source>Krouskop et al. 1998: 96-116 kPa at 5% precompression</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="17"/>
        <source>DCIS (Krouskop, 20%)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="17"/>
        <source>Krouskop et al. 1998: 291-307 kPa at 20% precompression</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="18"/>
        <source>Fibroglandular (Krouskop, 5%)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="18"/>
        <source>Krouskop et al. 1998: 28-35 kPa at 5% precompression</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="19"/>
        <source>IDC high grade (Samani)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="19"/>
        <source>Samani et al. 2007: 10-43 kPa by grade, small strain</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="20"/>
        <source>Fibroadenoma (Samani, 2x fat)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="20"/>
        <source>Samani et al. 2007: about 6.4 kPa</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::TumourPanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="247"/>
        <location filename="../ui/panels.cpp" line="275"/>
        <source>Source: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="276"/>
        <source>Preset</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="277"/>
        <source>Stiffness</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="278"/>
        <source>Add by shape</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="279"/>
        <source>Sphere</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="280"/>
        <source>Ellipsoid</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="281"/>
        <source>Shape</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="282"/>
        <source>Centre x, y, z</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="283"/>
        <source>Radius (x, y, z)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="284"/>
        <source>Add tumour</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="285"/>
        <source>Remove selected</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="286"/>
        <source>Brush</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="287"/>
        <source>Radius</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="288"/>
        <source>Depth below the skin</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="289"/>
        <source>Paint</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="290"/>
        <source>Erase</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="291"/>
        <source>Drag on the breast to paint tumour tissue (one undo step per stroke)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="292"/>
        <source>Drag on the breast to restore healthy tissue</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="293"/>
        <source>Undo</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="294"/>
        <source>Redo</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::VtkView</name>
    <message>
        <location filename="../ui/vtk_view.cpp" line="630"/>
        <source>no OpenGL context for a native window on this platform (%1)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/vtk_view.cpp" line="633"/>
        <source>the display&apos;s OpenGL (%1) has no stereo buffers; quad-buffer stereo needs a stereo-capable GPU, driver and display</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/vtk_view.cpp" line="847"/>
        <source>Quad-buffer stereo is not available: %1. Showing anaglyph (red/cyan glasses) instead; side-by-side and interlaced are also available.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/vtk_view.cpp" line="849"/>
        <source>the view is not initialised yet</source>
        <translation type="unfinished"></translation>
    </message>
</context>
</TS>

// Demo page logic (index.html): loads a compressed glTF with the
// EXT_normal_mesh_compression plugin, draws it, and lets the user step through
// its levels. URL parameters: model=URL (default models/stanford-bunny.glb, made
// by samples/web/make_models.sh), progressive=1 (coarsest level first),
// level=K (decode no further than K). window.eqmeshDemo is the hook
// tests/web/ drives the page through; body[data-state] says loading/ready/error.
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import createWasm from '../../build-wasm/eqmesh_decoder.mjs';
import { EqmeshDecoder, loadDracoDecoderModule } from '../../web/EqmeshDecoder.js';
import { GLTFNormalMeshCompressionExtension } from '../../web/EXTNormalMeshCompression.js';

const DRACO_PATH = '../../web/node_modules/three/examples/jsm/libs/draco/';
// A load that neither finishes nor fails in this time is reported, not waited on.
const LOAD_TIMEOUT_MS = 60000;

const params = new URLSearchParams( location.search );
const ui = {
	source: document.getElementById( 'source' ),
	level: document.getElementById( 'level' ),
	levelValue: document.getElementById( 'level-value' ),
	file: document.getElementById( 'file' ),
	stats: document.getElementById( 'stats' ),
	error: document.getElementById( 'error' ),
};
const viewer = createViewer( document.getElementById( 'view' ) );
const decoderPromise = loadDracoDecoderModule( DRACO_PATH ).then( ( draco ) => EqmeshDecoder.create( { createWasm, draco } ) );
// What is on show: { root, meshes, plugin, name, fileBytes, levelLog, info, loadMs }.
let current = null;

window.eqmeshDemo = { load, setLevel, decoder: decoderPromise, get current() { return current; } };

ui.level.addEventListener( 'input', () => setLevel( Number( ui.level.value ) ).catch( showError ) );
ui.file.addEventListener( 'change', () => {

	if ( ui.file.files.length ) load( { file: ui.file.files[ 0 ] } );

} );
load( { url: params.get( 'model' ) || 'models/stanford-bunny.glb' } );

// ---------------------------------------------------------------------------

async function load( source ) {

	setState( 'loading' );
	clearScene();
	const name = source.file ? source.file.name : source.url;
	ui.source.textContent = name;
	const started = performance.now();
	try {

		const entry = { name, levelLog: [], fileBytes: null, info: null };
		current = entry;
		const gltf = await withTimeout( parse( source, entry ), LOAD_TIMEOUT_MS, `${name}: no result after ${LOAD_TIMEOUT_MS / 1000} s` );
		show( entry, gltf, performance.now() - started );

	} catch ( error ) {

		showError( error, name );

	}

}

async function parse( source, entry ) {

	const decoder = await decoderPromise;
	const loader = new GLTFLoader();
	loader.register( ( parser ) => {

		entry.plugin = new GLTFNormalMeshCompressionExtension( parser, decoder, {
			progressive: params.get( 'progressive' ) === '1',
			maxLevel: params.has( 'level' ) ? Number( params.get( 'level' ) ) : - 1,
			onLevel: ( mesh, level, info ) => onLevel( entry, info ),
			onError: ( error ) => entry === current && showError( error ),
		} );
		return entry.plugin;

	} );
	if ( source.file ) return parseBytes( loader, await source.file.arrayBuffer(), '', entry );
	if ( ! /\.glb$/i.test( source.url ) ) return loader.loadAsync( source.url );
	const response = await fetch( source.url );
	if ( ! response.ok ) throw new Error( `HTTP ${response.status}${response.status === 404 ? ' (samples/web/make_models.sh makes the demo models)' : ''}` );
	return parseBytes( loader, await response.arrayBuffer(), THREE.LoaderUtils.extractUrlBase( response.url ), entry );

}

function parseBytes( loader, bytes, basePath, entry ) {

	entry.fileBytes = bytes.byteLength;
	return loader.parseAsync( bytes, basePath );

}

function withTimeout( promise, ms, message ) {

	let timer;
	const timeout = new Promise( ( resolve, reject ) => {

		timer = setTimeout( () => reject( new Error( message ) ), ms );

	} );
	return Promise.race( [ promise, timeout ] ).finally( () => clearTimeout( timer ) );

}

function show( entry, gltf, loadMs ) {

	const meshes = [];
	gltf.scene.traverse( ( o ) => o.isMesh && entry.plugin.levelsOf( o ) >= 0 && meshes.push( o ) );
	Object.assign( entry, { root: gltf.scene, meshes, loadMs } );
	viewer.show( gltf.scene );
	const levels = Math.max( 0, ...meshes.map( ( m ) => entry.plugin.levelsOf( m ) ) );
	ui.level.max = String( levels );
	ui.level.disabled = meshes.length === 0;
	if ( entry.info ) ui.level.value = String( entry.info.level );
	updateStats();
	setState( 'ready' );

}

// Called for every level shown, by the progressive refinement or by setLevel.
function onLevel( entry, info ) {

	entry.levelLog.push( { level: info.level, vertices: info.vertices, triangles: info.triangles } );
	entry.info = info;
	if ( entry !== current ) return;
	ui.level.value = String( info.level );
	updateStats();

}

// Shows level k of every compressed mesh; resolves to the infos, one per mesh.
async function setLevel( level ) {

	if ( ! current || ! current.meshes ) throw new Error( 'nothing loaded' );
	const infos = await Promise.all( current.meshes.map( ( m ) => current.plugin.setLevel( m, level ) ) );
	return infos;

}

function updateStats() {

	const e = current;
	const i = e.info;
	ui.levelValue.textContent = i ? `${i.level} of ${i.levels}` : '–';
	const lines = [];
	if ( e.fileBytes !== null ) lines.push( `file        ${e.fileBytes.toLocaleString( 'en' )} bytes` );
	if ( i ) {

		lines.push( `stream      ${i.bytes.toLocaleString( 'en' )} of ${i.streamBytes.toLocaleString( 'en' )} bytes` );
		lines.push( `mesh        ${i.vertices.toLocaleString( 'en' )} vertices, ${i.triangles.toLocaleString( 'en' )} triangles` );
		lines.push( `decode      ${i.decodeMs.toFixed( 1 )} ms (level ${i.level})` );

	}
	if ( e.loadMs !== undefined ) lines.push( `first show  ${e.loadMs.toFixed( 0 )} ms after load()` );
	if ( e.meshes && e.meshes.length === 0 ) lines.push( 'no EXT_normal_mesh_compression primitive' );
	ui.stats.textContent = lines.join( '\n' );

}

// `where` (the file) prefixes the message, as the native tools name the file.
function showError( error, where ) {

	console.error( error );
	const message = error && error.message ? error.message : String( error );
	ui.error.textContent = where ? `${where}: ${message}` : message;
	ui.error.classList.add( 'shown' );
	setState( 'error' );

}

function setState( state ) {

	document.body.dataset.state = state;
	if ( state === 'loading' ) {

		ui.error.classList.remove( 'shown' );
		ui.error.textContent = '';

	}

}

function clearScene() {

	viewer.show( null );
	ui.level.disabled = true;
	ui.stats.textContent = '';

}

// ---------------------------------------------------------------------------
// The 3D view: renderer, lights, orbit controls, and framing of what it shows.

function createViewer( container ) {

	const renderer = new THREE.WebGLRenderer( { antialias: true, preserveDrawingBuffer: true } );
	renderer.setPixelRatio( window.devicePixelRatio );
	container.appendChild( renderer.domElement );
	const scene = new THREE.Scene();
	scene.background = new THREE.Color( 0x2a2f37 );
	scene.add( new THREE.HemisphereLight( 0xffffff, 0x445566, 1.5 ) );
	const sun = new THREE.DirectionalLight( 0xffffff, 2.0 );
	sun.position.set( 1, 2, 3 );
	scene.add( sun );
	const camera = new THREE.PerspectiveCamera( 40, 1, 0.01, 1000 );
	const controls = new OrbitControls( camera, renderer.domElement );
	const content = new THREE.Group();
	scene.add( content );
	const resize = () => {

		renderer.setSize( container.clientWidth, container.clientHeight );
		camera.aspect = container.clientWidth / Math.max( 1, container.clientHeight );
		camera.updateProjectionMatrix();

	};
	window.addEventListener( 'resize', resize );
	resize();
	renderer.setAnimationLoop( () => {

		controls.update();
		renderer.render( scene, camera );

	} );
	return { show: ( object ) => showObject( content, object, camera, controls ) };

}

function showObject( content, object, camera, controls ) {

	content.clear();
	if ( ! object ) return;
	content.add( object );
	const box = new THREE.Box3().setFromObject( object );
	const center = box.getCenter( new THREE.Vector3() );
	const radius = Math.max( box.getSize( new THREE.Vector3() ).length() / 2, 1e-6 );
	camera.near = radius / 100;
	camera.far = radius * 100;
	camera.position.copy( center ).add( new THREE.Vector3( 0.4, 0.3, 1 ).normalize().multiplyScalar( radius * 2.6 ) );
	camera.updateProjectionMatrix();
	controls.target.copy( center );
	controls.update();

}
